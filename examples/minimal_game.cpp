// minimal_game: the smallest game that uses LPV Engine as an installed package.
//
// Overview: it loads a glTF scene and its own config (minimal_game.toml: GI on), renders a few
// frames headless with the deferred renderer and the light propagation volume, writes the last
// frame to a PNG and prints the frame profiler's summary (each pass's time and memory against
// the platform's budgets).
//
// Details: every frame a game (1) lets the GI update (it rebuilds its volumes when a gi.* setting
// changed, refuses settings over the platform's budget by throwing, and plans this frame's work),
// (2) opens a device frame and a profiler frame, (3) renders, passing the GI as the renderer's
// indirect light, and (4) closes both. The game owns the device, renderer, GI and profiler; the
// renderer owns its targets, the GI its volumes. All of it runs on the thread that made the
// device. docs/embedding.md says more.
//
//   minimal_game SCENE.gltf [--backend auto|vulkan|gl] [--frames N] [--screenshot out.png]
//                [--config game.toml] [--set key=value]...
#include "engine/DeviceSettings.h"
#include "engine/PlatformSettings.h"
#include "engine/Screenshot.h"
#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfileReport.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/Renderer.h"
#include "engine/scene/SceneLoading.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "rhi/Device.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

using namespace lpv;

namespace {

int run(int argc, char** argv) {
    std::string scenePath, screenshot, configPath = MINIMAL_GAME_CONFIG;
    std::vector<std::string> overrides;
    int frames = 3;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        const bool hasValue = i + 1 < argc;
        if (arg == "--backend" && hasValue)
            overrides.push_back(std::string("render.backend=") + argv[++i]);
        else if (arg == "--frames" && hasValue)
            frames = std::max(1, std::atoi(argv[++i]));
        else if (arg == "--screenshot" && hasValue)
            screenshot = argv[++i];
        else if (arg == "--config" && hasValue)
            configPath = argv[++i];
        else if (arg == "--set" && hasValue)
            overrides.push_back(argv[++i]);
        else if (!arg.starts_with("--") && scenePath.empty())
            scenePath = arg;
        else {
            std::fprintf(stderr,
                         "usage: %s SCENE.gltf [--backend B] [--frames N] [--screenshot PATH] "
                         "[--config FILE] [--set key=value]...\n",
                         argv[0]);
            return 2;
        }
    }
    if (scenePath.empty()) scenePath = "cornell"; // a built-in scene

    // Settings: the game's own TOML, then the command line.
    engine::Config config;
    config.loadFile(configPath);
    for (const std::string& assignment : overrides)
        config.applyOverride(assignment, "command line");

    const engine::Scene scene = engine::loadScene(scenePath);
    const uint32_t width = engine::renderWidth(config), height = engine::renderHeight(config);
    std::unique_ptr<rhi::Device> device = rhi::createDevice(engine::deviceConfigFrom(config)); // headless
    const platforms::PlatformProfile profile = engine::activePlatformProfile(config);          // the budgets
    std::printf("minimal_game: '%s' on %s (%s), %ux%u, platform profile '%s'\n", scene.name.c_str(),
                std::string(rhi::backendName(device->backend())).c_str(), device->caps().deviceName.c_str(),
                width, height, profile.name.c_str());

    engine::Renderer renderer(*device, width, height);
    renderer.setScene(scene);
    engine::FrameProfiler profiler(*device, profile);
    gi::LightPropagationVolume gi(*device, profile);
    const engine::CameraMatrices camera =
        engine::cameraMatrices(engine::defaultCamera(scene), float(width) / float(height));

    for (int frame = 0; frame < frames; ++frame) {
        // Settings over the platform's budget are refused; the GI keeps what it ran (off at first).
        if (const gi::GiConfigResult result = gi::updateFromConfig(gi, config, renderer, camera, &profiler);
            !result)
            throw std::runtime_error("GI settings refused: " + result.message());
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, camera, config, &profiler, gi.settings().enabled ? &gi : nullptr);
        profiler.endFrame(cmd);
        device->endFrame(renderer.output());
    }
    device->waitIdle();
    gi.collectPending(&profiler); // what the last frames' GPU work left to report

    if (!screenshot.empty()) {
        engine::writeScreenshot(*device, renderer, screenshot);
        std::printf("minimal_game: wrote %s\n", screenshot.c_str());
    }
    profiler.collectPending(); // the last frames' GPU timings
    std::fputs(engine::profileSummaryText(profiler).c_str(), stdout);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) { // a bad config or scene, no backend, a refused GI budget
        std::fprintf(stderr, "minimal_game: error: %s\n", e.what());
        return 1;
    }
}
