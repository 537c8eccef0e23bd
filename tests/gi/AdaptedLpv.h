// The real pipeline on the null device with the game's frame loop, for the budget tests: the
// scheduler reads the profiler's predicted console GI time of checked frames.
#pragma once

#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/Renderer.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/GiScheduler.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"
#include "rhi/Device.h"

#include "../support/TestDevice.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lpv::test {

// The real pipeline on the null device and `profile`, with the game's frame loop. The first
// constructor: gi.budget_policy=adapt, one cascade, RGBA8, RSM 128 and `iterations` on the Cornell
// box at 160x120. `camera` and the renderer's sun may be moved between frames.
struct AdaptedLpv {
    std::unique_ptr<rhi::Device> device = test::nullDevice();
    platforms::PlatformProfile profile;
    engine::Config config;
    engine::Scene scene;
    engine::Renderer renderer;
    engine::FrameProfiler profiler;
    gi::LightPropagationVolume lpv;
    engine::CameraMatrices camera;
    gi::GiConfigResult lastUpdate; // what the GI said of the last frame's settings

    AdaptedLpv(platforms::PlatformProfile p, uint32_t iterations)
        : AdaptedLpv(std::move(p),
                     {"gi.enabled=true", "gi.sh_format=rgba8", "gi.rsm_size=128", "gi.vpl_count=1024",
                      "gi.cascades=1", "gi.budget_policy=adapt",
                      "gi.iterations=" + std::to_string(iterations)},
                     engine::buildCornellBox(), 160, 120) {}
    AdaptedLpv(platforms::PlatformProfile p, const std::vector<std::string>& overrides, engine::Scene s,
               uint32_t width, uint32_t height)
        : AdaptedLpv(std::move(p), {}, overrides, std::move(s), width, height) {}
    // Config files first, then the overrides, as the game applies --config and --set.
    AdaptedLpv(platforms::PlatformProfile p, const std::vector<std::string>& configFiles,
               const std::vector<std::string>& overrides, engine::Scene s, uint32_t width, uint32_t height)
        : profile(std::move(p)), scene(std::move(s)), renderer(*device, width, height),
          profiler(*device, profile), lpv(*device, profile),
          camera(engine::cameraMatrices(*scene.camera, float(width) / float(height))) {
        for (const std::string& f : configFiles)
            config.loadFile(f);
        for (const std::string& o : overrides)
            config.applyOverride(o, "test");
        renderer.setScene(scene);
    }
    // One frame; the GI cost the scheduler will see next.
    std::optional<gi::GiFrameCost> frame() {
        lastUpdate = gi::updateFromConfig(lpv, config, renderer, camera, &profiler);
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, camera, config, &profiler, &lpv);
        profiler.endFrame(cmd);
        device->endFrame();
        return gi::giFrameCost(profiler);
    }
};

} // namespace lpv::test
