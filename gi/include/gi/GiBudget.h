// What a GI configuration allocates, computed before anything is made, so a configuration that
// does not fit the platform profile is refused with a list of its resources, their bytes and the
// overage (the frame profiler's memory figures later show the same numbers, measured).
#pragma once

#include "gi/LpvSettings.h"
#include "platforms/PlatformProfile.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace lpv::gi {

struct GiResource {
    std::string name;
    std::string category; // gi.rsm, gi.vpl, gi.lpv
    uint64_t bytes = 0;
};

std::vector<GiResource> giResources(const LpvSettings& settings);
uint64_t giBytes(const std::vector<GiResource>& resources);

class GiBudgetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Throws GiBudgetError when the format, the grid or the memory does not fit `profile`.
void checkGiBudget(const LpvSettings& settings, const platforms::PlatformProfile& profile);

} // namespace lpv::gi
