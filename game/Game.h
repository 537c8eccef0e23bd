// The sample game: a scene, the renderer and the profiler driven by config, headless or in a
// window, writing a screenshot and a profile report on request.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace lpv::game {

struct GameOptions {
    std::vector<std::string> configFiles;
    // (source, key=value): --set and the shorthand flags, in order.
    std::vector<std::pair<std::string, std::string>> overrides;
    std::string scene = "cornell";
    int frames = -1; // -1: 1 headless, until closed in a window
    bool headless = false;
    std::string screenshot;
    std::string cameraPath;
    std::string profileOut;
};

// Returns the process exit code; throws engine::ConfigError, engine::SceneError,
// rhi::BackendUnavailable and std::exception for the caller to report.
int runGame(const GameOptions& options);

} // namespace lpv::game
