// What a GI configuration allocates, computed before anything is made, so a configuration that
// does not fit the platform profile is refused with a list of its resources, their bytes and the
// overage (the frame profiler's memory figures later show the same numbers, measured).
#pragma once

#include "gi/GiConfigResult.h"
#include "gi/LpvSettings.h"
#include "platforms/PlatformProfile.h"

#include <cstdint>
#include <vector>

namespace lpv::gi {

std::vector<GiResource> giResources(const LpvSettings& settings);
uint64_t giBytes(const std::vector<GiResource>& resources);

// Refuses a format, a grid or a memory total that does not fit `profile`. Run when a configuration
// changes the GI's resources, never in a steady-state frame (it lists them on the heap).
GiConfigResult checkGiBudget(const LpvSettings& settings, const platforms::PlatformProfile& profile);

} // namespace lpv::gi
