// What the LPV asks of a device beyond the APIs' minimums, refused with a message that says so.
#include "gi/LightPropagationVolume.h"
#include "platforms/PlatformProfile.h"
#include "rhi/Backend.h"
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <doctest/doctest.h>

#include <string>

using namespace lpv;

TEST_CASE("gi: a device with too few fragment texture bindings for the lookup is refused with the count") {
    const auto lpvOn = [](uint32_t bindings) {
        rhi::DeviceConfig config;
        config.backend = rhi::BackendKind::Null;
        config.fragmentTextureBindings = bindings;
        const std::unique_ptr<rhi::Device> device = rhi::createDevice(config);
        REQUIRE(device->caps().fragmentTextureBindings == bindings);
        try {
            gi::LightPropagationVolume lpv(*device, platforms::loadPlatformProfile("pc"));
        } catch (const rhi::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // OpenGL 4.5's and Vulkan's minimum: the lookup binds up to binding 20.
    const std::string refused = lpvOn(16);
    CHECK(refused.find("binding 20") != std::string::npos);
    CHECK(refused.find("allows 16") != std::string::npos);
    CHECK(lpvOn(21).empty());
}
