// What the LPV asks of a device beyond the APIs' minimums, refused with a message that says so.
#include "gi/LightPropagationVolume.h"
#include "gi/LpvPropagation.h"
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

TEST_CASE("gi: gi.gather on a device with too few fragment texture bindings is refused, naming it") {
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    config.fragmentTextureBindings = gi::IndirectLookup::kGatherTextureBindings - 1;
    const std::unique_ptr<rhi::Device> device = rhi::createDevice(config);
    gi::LightPropagationVolume lpv(*device, platforms::loadPlatformProfile("pc"));
    gi::LpvSettings s;
    s.enabled = true;
    s.gatherMode = gi::LpvSettings::Gather::On;
    const gi::GiConfigResult refused = lpv.update(s, gi::GiFrameInputs{}, nullptr);
    CHECK_FALSE(refused.accepted);
    CHECK(refused.setting == "gi.gather");
    CHECK(refused.reason.find("allows " + std::to_string(gi::IndirectLookup::kGatherTextureBindings - 1)) !=
          std::string::npos);
    // auto leaves it off there.
    s.gatherMode = gi::LpvSettings::Gather::Auto;
    CHECK(lpv.update(s, gi::GiFrameInputs{}, nullptr).accepted);
    CHECK_FALSE(lpv.settings().gather);
}

TEST_CASE("gi: the volumes propagate stacked only where a GPU's branches and bindings allow") {
    // A GPU with the bindings the stacked kernels take (LpvPropagation::stacks).
    rhi::Caps gpu;
    gpu.maskedBranches = false;
    gpu.storageImageBindings = 32;
    gpu.computeTextureBindings = 32;
    gpu.max3DTextureSize = 2048;
    gi::LpvSettings s; // float volumes
    s.cascades = 3;    // with a shell
    CHECK(gi::LpvPropagation::stacks(gpu, s, 4));
    CHECK(gi::LpvPropagation::stacks(gpu, s, 2));
    CHECK_FALSE(gi::LpvPropagation::stacks(gpu, s, 1));
    // A CPU rasterizer runs every side of the kernels' switches.
    rhi::Caps cpu = gpu;
    cpu.maskedBranches = true;
    CHECK_FALSE(gi::LpvPropagation::stacks(cpu, s, 4));
    // NVIDIA's GL driver: 8 storage images, where the stacked last step binds 15.
    rhi::Caps narrow = gpu;
    narrow.storageImageBindings = 8;
    CHECK_FALSE(gi::LpvPropagation::stacks(narrow, s, 4));
    narrow = gpu;
    narrow.computeTextureBindings = 16;
    CHECK_FALSE(gi::LpvPropagation::stacks(narrow, s, 4));
    // Vulkan's minimum 3D size (256) holds four 34-cell slabs of a 32^3 grid, not four of 64^3.
    rhi::Caps small = gpu;
    small.max3DTextureSize = 256;
    CHECK(gi::LpvPropagation::stacks(small, s, 4));
    s.gridSize = 64;
    CHECK_FALSE(gi::LpvPropagation::stacks(small, s, 4));
    s.gridSize = 32;
    // One cascade has no shell; rgba8 keeps one set.
    gi::LpvSettings single = s;
    single.cascades = 1;
    CHECK_FALSE(gi::LpvPropagation::stacks(gpu, single, 4));
    gi::LpvSettings rgba8 = s;
    rgba8.shFormat = gi::ShFormat::Rgba8;
    CHECK_FALSE(gi::LpvPropagation::stacks(gpu, rgba8, 4));
}
