// libFuzzer harness for the TOML settings loaders: Config::loadString (what --config files go
// through) and parsePlatformProfile (a platform.profile given as a file), each input through both.
// Bad input must end in a ConfigError (a profile's: a std::runtime_error naming file and line);
// any other exception, a crash or a sanitizer report is a finding.
#include "engine/config/Config.h"
#include "platforms/Log.h"
#include "platforms/PlatformProfile.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string_view>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    lpv::log::setSink([](lpv::log::Level, std::string_view) {}); // warnings would flood the run
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    lpv::engine::Config config;
    try {
        config.loadString(text, "fuzz.toml");
        config.applyPending();
    } catch (const lpv::engine::ConfigError&) {
        // The expected refusal: a message naming the source and line.
    } catch (const std::exception& e) {
        std::fprintf(stderr, "not a ConfigError: %s\n", e.what());
        std::abort();
    }
    try {
        const lpv::platforms::PlatformProfile profile =
            lpv::platforms::parsePlatformProfile(text, "profile.toml");
        (void)profile;
    } catch (const std::runtime_error&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "profile: not a runtime_error: %s\n", e.what());
        std::abort();
    }
    return 0;
}
