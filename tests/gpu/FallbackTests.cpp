// Backend fallback when the Vulkan loader finds no driver. ctest runs this suite with
// VK_DRIVER_FILES pointing at a file that does not exist.
#include "platforms/Log.h"
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>
#include <vector>

using namespace lpv;

TEST_SUITE("driverless") {
    TEST_CASE("vulkan without a driver falls back to GL when allowed, and fails clearly when not") {
        REQUIRE_MESSAGE(std::getenv("VK_DRIVER_FILES") != nullptr, "run with VK_DRIVER_FILES=/nonexistent");
        std::vector<std::string> lines;
        auto previous = log::setSink([&](log::Level level, std::string_view m) {
            if (level >= log::Level::Warning) lines.emplace_back(m);
        });

        rhi::DeviceConfig config;
        config.backend = rhi::BackendKind::Vulkan;
        config.allowFallback = true;
        {
            auto device = rhi::createDevice(config);
            CHECK(device->backend() == rhi::BackendKind::OpenGL);
        }
        REQUIRE(lines.size() == 1);
        CHECK(lines[0].find("'vulkan'") != std::string::npos);
        CHECK(lines[0].find("'gl'") != std::string::npos);
        CHECK(lines[0].find("falling back") != std::string::npos);

        config.allowFallback = false;
        std::string message;
        try {
            rhi::createDevice(config);
        } catch (const rhi::BackendUnavailable& e) {
            message = e.what();
        }
        MESSAGE("error without fallback: " << message);
        CHECK(message.find("vulkan") != std::string::npos);
        CHECK(message.find("fallback not allowed") != std::string::npos);
        log::setSink(previous);
    }
}
