// Errors the RHI reports to its caller. Misuse (a stale handle, a bad descriptor) and a backend
// that cannot start are exceptions with a message a person can act on; they are never ignored.
#pragma once

#include <stdexcept>
#include <string>

namespace lpv::rhi {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A backend could not be created (no driver, missing extension, context creation failed).
class BackendUnavailable : public Error {
public:
    using Error::Error;
};

} // namespace lpv::rhi
