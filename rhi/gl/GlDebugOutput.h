// KHR_debug plumbing: the message callback that feeds DeviceConfig::onDebugMessage, and object
// labels so a capture or a debug message names the RHI object.
#pragma once

#include "GlFunctions.h"

#include "rhi/Backend.h"

#include <string_view>

namespace lpv::rhi::gl {

// Installs a synchronous callback (messages arrive on the call that caused them). `config` must
// outlive the context's use of it; uninstallDebugOutput() detaches it.
void installDebugOutput(const Functions& gl, const DeviceConfig& config);
void uninstallDebugOutput(const Functions& gl);

class ObjectLabeler {
public:
    void init(const Functions& gl);
    // Names longer than GL_MAX_LABEL_LENGTH are cut (GL would reject them with an error).
    void operator()(GLenum type, GLuint id, std::string_view name) const;

private:
    const Functions* gl_ = nullptr;
    GLsizei maxLength_ = 256;
};

} // namespace lpv::rhi::gl
