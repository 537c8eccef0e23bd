// LPV Engine sample game: command line to GameOptions, errors to messages and exit codes.
//   exit 0: ran; 1: runtime failure; 2: bad input (config, scene, arguments); 3: no backend.
#include "Game.h"

#include "engine/config/Config.h"
#include "engine/config/EmptyOptionValue.h"
#include "engine/config/Setting.h"
#include "engine/config/SettingsHelp.h"
#include "engine/scene/SceneLoading.h"
#include "rhi/Error.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

using namespace lpv;

namespace {

// The "did you mean" that a misspelt setting gets, for a misspelt option; any other argument
// left over is named as unexpected.
void reportMisspeltOptions(const CLI::App& app) {
    std::vector<std::string> options;
    for (const CLI::Option* option : app.get_options())
        for (const std::string& name : option->get_lnames())
            options.push_back("--" + name);
    bool optionsEnded = false; // after `--` an argument is not an option, and the game takes none
    for (const std::string& arg : app.remaining()) {
        if (arg == "--" && !optionsEnded) {
            optionsEnded = true;
            continue;
        }
        if (optionsEnded || !arg.starts_with("--")) {
            std::fprintf(stderr, "error: unexpected argument '%s'\n", arg.c_str());
            continue;
        }
        const std::string flag = arg.substr(0, arg.find('='));
        const std::string suggestion = engine::nearestName(flag, options);
        const std::string hint = suggestion.empty() ? "" : " (did you mean '" + suggestion + "'?)";
        std::fprintf(stderr, "error: unknown option '%s'%s\n", flag.c_str(), hint.c_str());
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"LPV Engine sample game: dynamic global illumination with light propagation volumes"};
    game::GameOptions opt;
    std::string helpConfig;
    // --set and the shorthands that stand for it take effect in the order given, the later one
    // winning, as between two --set: each occurrence's callback runs as it is parsed
    // (trigger_on_parse; after parsing, CLI11 would run them in the order they are declared here).
    const auto shorthand = [&](const char* flag, const char* key, const char* description) {
        app.add_option_function<std::string>(
               flag,
               [&opt, flag, key](const std::string& v) {
                   opt.overrides.emplace_back(flag, std::string(key) + "=" + v);
               },
               description)
            ->trigger_on_parse();
    };
    const auto shorthandFlag = [&](const char* flag, const char* assignment, const char* description) {
        // Runs for a true value only: --validation=false asks for nothing.
        app.add_flag_callback(
               flag, [&opt, flag, assignment] { opt.overrides.emplace_back(flag, assignment); }, description)
            ->trigger_on_parse();
    };
    app.add_option("--config", opt.configFiles, "TOML config file(s), applied in order");
    app.add_option_function<std::vector<std::string>>(
           "--set",
           [&](const std::vector<std::string>& v) {
               for (const std::string& a : v)
                   opt.overrides.emplace_back("--set", a);
           },
           "Override a setting: --set render.exposure=1.5 (after the config files)")
        ->trigger_on_parse();
    app.add_option("--scene", opt.scene, "Built-in scene (cornell, atrium, lights) or a .gltf/.glb path")
        ->capture_default_str()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    shorthand("--backend", "render.backend",
              "Graphics backend: auto, gl, vulkan, null (= --set render.backend=...)");
    shorthand("--gl-platform", "render.gl_platform", "Headless GL context: egl or osmesa");
    shorthandFlag("--no-fallback", "render.allow_fallback=false",
                  "Fail instead of falling back to the other backend (needs a named --backend)");
    shorthandFlag("--validation", "render.validation=true", "Vulkan validation layer / GL debug output");
    shorthand("--width", "render.width", "Frame width");
    shorthand("--height", "render.height", "Frame height");
    shorthand("--platform", "platform.profile",
              "Budget profile: x360, ps3, pc or a file (= --set platform.profile=...)");
    app.add_flag("--headless", opt.headless, "Never open a window");
    app.add_option("--frames", opt.frames,
                   "Frames to render, 1 or more (default: 1 headless, until closed in a window)")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    // Given twice (./lpv.sh run passes its own, then the caller's), the last one wins.
    app.add_option("--screenshot", opt.screenshot,
                   "Write the last frame: .png (sRGB) or .exr/.pfm (linear HDR); the last one given wins")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--camera-path", opt.cameraPath, "Scripted camera over the frames: orbit or flythrough")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--profile-out", opt.profileOut,
                   "Write the profiler's trace, summary and chart into this folder; the last one given wins")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    app.add_option("--help-config", helpConfig,
                   "List every setting and exit: as text, or as a Markdown table with 'markdown'")
        ->expected(0, 1);
    if (engine::refuseEmptyOptionValue(argc, argv)) return 2;
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) { // --help
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // A bad command line is bad input (exit 2), whatever CLI11's own code for it. Arguments
        // left over are named once each by reportMisspeltOptions, an unknown option with a hint.
        if (dynamic_cast<const CLI::ExtrasError*>(&e) == nullptr)
            std::fprintf(stderr, "error: %s\n", e.what());
        reportMisspeltOptions(app);
        std::fputs("Run with --help for more information.\n", stderr);
        return 2;
    }
    // 0 is not "until closed": a window runs until closed when --frames is not given.
    if (app.count("--frames") && opt.frames < 1) {
        std::fprintf(stderr, "error: --frames: expected a positive number of frames, got %d\n", opt.frames);
        return 2;
    }
    // An empty path would write nothing, silently.
    for (const auto& [flag, path] :
         {std::pair<const char*, const std::string*>{"--screenshot", &opt.screenshot},
          {"--profile-out", &opt.profileOut}})
        if (app.count(flag) && path->empty()) {
            std::fprintf(stderr, "error: %s: expected a path, got an empty one\n", flag);
            return 2;
        }
    if (app.count("--help-config")) {
        if (!helpConfig.empty() && helpConfig != "markdown") {
            std::fprintf(stderr, "error: --help-config: expected 'markdown' or nothing, got '%s'\n",
                         helpConfig.c_str());
            return 2;
        }
        std::fputs(
            (helpConfig == "markdown" ? engine::settingsMarkdownTable() : engine::settingsHelpText()).c_str(),
            stdout);
        return 0;
    }
    try {
        return game::runGame(opt);
    } catch (const engine::ConfigError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const engine::SceneError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const rhi::BackendUnavailable& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 3;
    } catch (const game::OutputError& e) {
        for (const std::string& failure : e.failures())
            std::fprintf(stderr, "error: %s\n", failure.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
