// The platform.profile setting and its loading.
#include "engine/PlatformSettings.h"

#include <stdexcept>

namespace lpv::engine {
namespace {
// Read once at startup: the profiler and the GI take the profile when they are made (and the GI's
// resources were checked against its limits), so a change while running waits for a restart.
const StringSetting kProfile{"platform.profile", "pc",
                             "Budget profile: x360, ps3, pc, or the path of a profile TOML file",
                             Apply::Restart};
} // namespace

platforms::PlatformProfile activePlatformProfile(const Config& config) {
    try {
        return platforms::loadPlatformProfile(config.get(kProfile));
    } catch (const std::runtime_error& e) {
        throw ConfigError(config.origin(kProfile.decl()), 0, "platform.profile: " + std::string(e.what()));
    }
}

} // namespace lpv::engine
