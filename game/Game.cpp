// The game loop.
#include "Game.h"

#include "Console.h"
#include "FreeCamera.h"

#include "engine/DeviceSettings.h"
#include "engine/ImageFile.h"
#include "engine/PlatformSettings.h"
#include "engine/Screenshot.h"
#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfileReport.h"
#include "engine/profiler/ProfilerOverlay.h"
#include "engine/render/CameraPath.h"
#include "engine/render/Renderer.h"
#include "engine/scene/SceneLoading.h"
#include "gi/GiBudget.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/Clock.h"
#include "platforms/Log.h"
#include "platforms/Platform.h"
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace lpv::game {
namespace {

const engine::FloatSetting kSceneDetail{
    "scene.detail",
    1.0,
    0.05,
    4.0,
    "Tessellation scale of the built-in atrium (1.0 = about 250k triangles)",
    engine::Apply::Restart};
const engine::FloatSetting kCameraSpeed{"game.camera_speed", 3.0, 0.1, 100.0,
                                        "Free camera speed in metres per second"};

// Stages the next value of an enum setting (a key cycles through its choices).
void cycle(engine::Config& config, const char* name) {
    const engine::SettingDecl* d = engine::SettingRegistry::global().find(name);
    if (!d || d->type != engine::SettingType::Enum) return;
    const std::string& current = std::get<std::string>(config.value(*d));
    size_t i = 0;
    while (i < d->choices.size() && d->choices[i] != current)
        ++i;
    config.stage(*d, d->choices[(i + 1) % d->choices.size()], "key");
}

void toggle(engine::Config& config, const char* name) {
    const engine::SettingDecl* d = engine::SettingRegistry::global().find(name);
    if (!d || d->type != engine::SettingType::Bool) {
        log::info(std::string("game: no setting '") + name + "' in this build");
        return;
    }
    config.stage(*d, !std::get<bool>(config.value(*d)), "key");
}

// The GI's "indirect" view is the renderer's indirect view: gi.debug_view=indirect, from a file,
// the command line or a key, shows what render.debug_view=indirect does.
void followGiIndirectView(engine::Config& config, const std::string& source) {
    const engine::SettingDecl* gi = engine::SettingRegistry::global().find("gi.debug_view");
    if (gi && std::get<std::string>(config.value(*gi)) == "indirect")
        config.set(*engine::SettingRegistry::global().find("render.debug_view"), std::string("indirect"),
                   source);
}

} // namespace

OutputError::OutputError(std::vector<std::string> failures)
    : std::runtime_error(failures.empty() ? std::string("no output failed") : failures.front()),
      failures_(std::move(failures)) {}

int runGame(const GameOptions& opt) {
    engine::Config config;
    for (const std::string& file : opt.configFiles)
        config.loadFile(file);
    for (const auto& [source, assignment] : opt.overrides)
        config.applyOverride(assignment, source);
    followGiIndirectView(config, "gi.debug_view");
    if (!opt.cameraPath.empty() && !engine::isCameraPath(opt.cameraPath))
        throw engine::ConfigError("--camera-path", 0,
                                  "unknown camera path '" + opt.cameraPath + "' (orbit, flythrough)");
    if (!opt.screenshot.empty()) {
        try {
            engine::imageFormatOf(opt.screenshot);
        } catch (const std::invalid_argument& e) {
            throw engine::ConfigError("--screenshot " + opt.screenshot, 0, e.what());
        }
    }
    // Output paths are checked before the run, not found bad after it.
    try {
        if (!opt.screenshot.empty()) platforms::Platform::checkWritable(opt.screenshot);
    } catch (const std::runtime_error& e) {
        throw engine::ConfigError("--screenshot", 0, e.what());
    }
    try {
        if (!opt.profileOut.empty()) {
            platforms::Platform::createDirectories(opt.profileOut);
            for (const char* name : engine::kProfileOutputFiles)
                platforms::Platform::checkWritable(opt.profileOut + "/" + name);
        }
    } catch (const std::runtime_error& e) {
        throw engine::ConfigError("--profile-out", 0, e.what());
    }
    rhi::DeviceConfig deviceConfig = engine::deviceConfigFrom(config);
    const platforms::PlatformProfile profile = engine::activePlatformProfile(config);
    const uint32_t width = engine::renderWidth(config), height = engine::renderHeight(config);

    uint64_t t0 = platforms::nowNanoseconds();
    const engine::Scene scene = engine::loadScene(opt.scene, float(config.get(kSceneDetail)));
    log::info("game: scene '" + scene.name + "': " + std::to_string(scene.triangleCount()) + " triangles, " +
              std::to_string(scene.instances.size()) + " instances, " + std::to_string(scene.lights.size()) +
              " lights (" + std::to_string((platforms::nowNanoseconds() - t0) / 1000000) + " ms)");
    // What the scene leaves to the engine's defaults, said rather than assumed.
    if (std::none_of(scene.lights.begin(), scene.lights.end(),
                     [](const engine::Light& l) { return l.type == engine::LightType::Directional; }))
        log::info("game: scene '" + scene.name +
                  "' has no directional light: the renderer's default sun lights it (a directional light of "
                  "intensity 0 turns it off)");
    if (!scene.camera)
        log::info("game: scene '" + scene.name + "' has no camera: a default one looks at its bounds");

    const std::unique_ptr<platforms::Platform> platform =
        platforms::Platform::create(!opt.headless, platforms::WindowDesc{width, height, "LPV Engine"});

    // Like a backend that cannot start: said, with GLFW's reason, and refused without fallback.
    // Without any display configured (DISPLAY unset: CI, a server) headless is what was asked for.
    if (!platform->window() && !opt.headless && !platforms::Window::displayConfigured()) {
        log::info("game: no display configured (DISPLAY is not set): headless");
    } else if (!platform->window() && !opt.headless) {
        if (!deviceConfig.allowFallback)
            throw rhi::BackendUnavailable("no window (" + platform->windowError() +
                                          "); falling back to headless not allowed (--headless runs "
                                          "without one)");
        log::warn("game: no window (" + platform->windowError() + "); falling back to headless");
    }
    deviceConfig.window = platform->window();
    t0 = platforms::nowNanoseconds();
    std::unique_ptr<rhi::Device> device = rhi::createDevice(deviceConfig);
    log::info("game: running on backend '" + std::string(rhi::backendName(device->backend())) + "' (" +
              device->caps().deviceName + ", " +
              std::to_string((platforms::nowNanoseconds() - t0) / 1000000) + " ms to create)" + ", " +
              platform->name() + ", platform profile '" + profile.name + "'");

    t0 = platforms::nowNanoseconds();
    engine::Renderer renderer(*device, width, height);
    renderer.setScene(scene);
    engine::FrameProfiler profiler(*device, profile);
    gi::LightPropagationVolume lpv(*device, profile);
    lpv.setScene(scene); // gi.cell_size = auto sizes the volume to the room around the camera
    // The overlay goes on frames that are presented, not on screenshots of headless runs.
    std::unique_ptr<engine::ProfilerOverlay> overlay;
    if (device->caps().presentation) overlay = std::make_unique<engine::ProfilerOverlay>(*device);
    // The gi.* values of the last configuration that fitted the budget, with where each came from,
    // restored when a change made while running does not fit. The origins come back too: a check
    // may depend on them (gi.debug_slice's default is clamped to a small volume, a chosen slice is
    // not), and a value restored as a new choice could be refused on every frame after.
    struct KeptSetting {
        const engine::SettingDecl* decl;
        engine::SettingValue value;
        std::string origin;
    };
    std::vector<KeptSetting> lastGoodGi;
    const engine::SettingDecl* renderView = engine::SettingRegistry::global().find("render.debug_view");
    bool firstFrame = true;
    const engine::Camera start = engine::defaultCamera(scene);
    FreeCamera freeCamera(start);
    Console console;
    // What a team waits for before the first frame (the renderer's and the GI's pipelines, the
    // scene's upload), and the line a script waits for before its signals land in a frame.
    log::info("game: ready to render after " + std::to_string((platforms::nowNanoseconds() - t0) / 1000000) +
              " ms of setup (renderer, profiler, GI)");

    // Until closed when presenting to a window, else one frame unless --frames says otherwise.
    const int frames = opt.frames > 0 ? opt.frames : (device->caps().presentation ? 0 : 1);
    uint64_t last = platforms::nowNanoseconds();
    bool minimised = false;
    for (int frame = 0; frames == 0 || frame < frames;) {
        // Minimised, it waits for the window to come back (a tenth of a second at a time) rather
        // than spin; such a wait draws nothing and is not one of the --frames.
        platform->pollEvents(minimised ? 0.1 : 0.0);
        const uint64_t now = platforms::nowNanoseconds();
        const float dt = float(now - last) / 1e9f;
        last = now;
        if (platform->quitRequested()) {
            if (const char* signal = platform->quitSignalName())
                log::info(std::string("game: ") + signal + " after " + std::to_string(frame) +
                          " frames: ending the run and writing its outputs (a second one stops it at once)");
            break;
        }
        if (platform->keyPressed(GLFW_KEY_F1)) cycle(config, "render.debug_view");
        if (platform->keyPressed(GLFW_KEY_F2)) cycle(config, "gi.debug_view");
        if (platform->keyPressed(GLFW_KEY_G)) toggle(config, "gi.enabled");
        // The console's lines wait for the second frame: the first checks the startup configuration,
        // whose errors end the run, and a line that arrived before it (piped in) is a change to be
        // refused and undone like any other, not part of what the game started with.
        for (const std::string& line : firstFrame ? std::vector<std::string>{} : console.takeLines()) {
            // Enter alone, or a comment (as in a config file): nothing to change, nothing to say.
            const size_t first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#') continue;
            // A comment after the setting too, from a '#' after white space (a value may hold '#').
            std::string setting = line;
            for (size_t k = first + 1; k < setting.size(); ++k)
                if (setting[k] == '#' && (setting[k - 1] == ' ' || setting[k - 1] == '\t')) {
                    setting.erase(setting.find_last_not_of(" \t", k - 1) + 1);
                    break;
                }
            try {
                config.stage(setting, "console");
            } catch (const engine::ConfigError& e) {
                log::error(e.what());
            }
        }
        uint32_t fw = 0, fh = 0;
        platform->frameSize(fw, fh);
        minimised = fw == 0 || fh == 0;
        if (minimised) continue;
        const std::vector<const engine::SettingDecl*> changes = config.applyPending();
        // render.debug_view as it was before gi.debug_view moved it: a refused GI change undoes that too.
        std::optional<KeptSetting> viewBeforeFollow;
        for (const engine::SettingDecl* changed : changes) {
            if (changed->name == "gi.debug_view") {
                viewBeforeFollow =
                    KeptSetting{renderView, config.value(*renderView), config.origin(*renderView)};
                followGiIndirectView(config, changed->name);
            }
            log::info("game: " + changed->name + " = " + changed->format(config.value(*changed)) +
                      (changed->apply == engine::Apply::Restart ? " (takes effect after a restart)" : ""));
        }

        engine::Camera cam = freeCamera.camera();
        if (!opt.cameraPath.empty())
            cam = engine::cameraOnPath(opt.cameraPath, scene.bounds, start,
                                       frames > 1 ? float(frame) / float(frames - 1) : 0.0f);
        else if (freeCamera.update(*platform, dt, float(config.get(kCameraSpeed))))
            cam = freeCamera.camera();
        const engine::CameraMatrices matrices = engine::cameraMatrices(cam, float(width) / float(height));
        // A GI configuration refused at startup ends the run; refused while running, the GI goes on
        // with what ran before, and the config shows it again: the refused values are undone.
        if (const gi::GiConfigResult result =
                gi::updateFromConfig(lpv, config, renderer, matrices, &profiler);
            !result) {
            if (firstFrame) throw engine::ConfigError("gi settings", 0, result.message());
            log::error("game: GI change refused (the previous GI settings come back): " + result.message());
            for (const KeptSetting& k : lastGoodGi)
                config.stage(*k.decl, k.value, k.origin);
            if (viewBeforeFollow)
                config.stage(*renderView, viewBeforeFollow->value, viewBeforeFollow->origin);
            // At once, before any new input can mix in.
            for (const engine::SettingDecl* restored : config.applyPending())
                log::info("game: " + restored->name + " = " + restored->format(config.value(*restored)) +
                          " (restored)");
        }
        if (firstFrame || !changes.empty()) {
            lastGoodGi.clear();
            for (const engine::SettingDecl* d : engine::SettingRegistry::global().all())
                if (d->name.starts_with("gi."))
                    lastGoodGi.push_back({d, config.value(*d), config.origin(*d)});
        }
        firstFrame = false;

        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, matrices, config, &profiler, lpv.settings().enabled ? &lpv : nullptr);
        if (overlay) overlay->draw(cmd, profiler, renderer.output());
        profiler.endFrame(cmd);
        device->endFrame(renderer.output());
        ++frame;
    }
    device->waitIdle();
    lpv.collectPending(&profiler); // what the last frames' GPU work left to report

    // Every output that can be written is, and the summary is printed, whatever failed.
    std::vector<std::string> failures;
    if (!opt.screenshot.empty()) {
        // Said, not left for the user to find in the file.
        if (!device->caps().drawsPixels)
            log::warn("game: the '" + std::string(rhi::backendName(device->backend())) +
                      "' backend draws nothing: " + opt.screenshot + " is black");
        // The volume slice and the VPLs are drawn over the tone-mapped frame, which a .exr or .pfm
        // (the HDR frame before tone mapping) does not hold.
        const gi::GiDebugView view = lpv.settings().debugView;
        if (lpv.settings().enabled &&
            (view == gi::GiDebugView::VolumeSlice || view == gi::GiDebugView::Vpls) &&
            engine::imageFormatOf(opt.screenshot) != engine::ImageFormat::Png)
            log::warn(std::string("game: gi.debug_view=") +
                      (view == gi::GiDebugView::Vpls ? "vpls" : "volume_slice") +
                      " is drawn over the tone-mapped frame: " + opt.screenshot +
                      " (HDR, before tone mapping) does not show it; a .png does");
        try {
            engine::writeScreenshot(*device, renderer, opt.screenshot);
            log::info("game: wrote " + opt.screenshot + " (backend '" +
                      std::string(rhi::backendName(device->backend())) + "')");
        } catch (const std::exception& e) {
            failures.emplace_back(e.what());
        }
    }
    // A short summary at exit; the full table is in summary.md.
    profiler.collectPending(); // the last frames' GPU timings
    std::string fullReport;
    if (!opt.profileOut.empty()) {
        try {
            engine::writeProfileOutputs(profiler, opt.profileOut);
            fullReport = opt.profileOut + "/summary.md (trace.json, summary.csv and frames.svg beside it)";
        } catch (const std::exception& e) {
            failures.emplace_back(e.what());
        }
    }
    std::fputs(engine::profileShortSummary(profiler, fullReport).c_str(), stdout);
    if (!failures.empty()) throw OutputError(std::move(failures));
    return 0;
}

} // namespace lpv::game
