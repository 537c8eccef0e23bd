// platform.profile: which console-class budget the game is measured against.
#pragma once

#include "engine/config/Config.h"
#include "platforms/PlatformProfile.h"

namespace lpv::engine {

// Loads the profile named by platform.profile; throws ConfigError naming the setting's origin.
platforms::PlatformProfile activePlatformProfile(const Config& config);

} // namespace lpv::engine
