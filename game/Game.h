// The sample game: a scene, the renderer and the profiler driven by config, headless or in a
// window, writing a screenshot and a profile report on request.
#pragma once

#include <stdexcept>
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

// The outputs that could not be written at the end of a run (the others were): one message per
// failure, naming the path and the reason.
class OutputError : public std::runtime_error {
public:
    explicit OutputError(std::vector<std::string> failures);
    const std::vector<std::string>& failures() const { return failures_; }

private:
    std::vector<std::string> failures_;
};

// Returns the process exit code; throws engine::ConfigError (also for an output path that cannot
// be written, found before the first frame), engine::SceneError, rhi::BackendUnavailable,
// OutputError and std::exception for the caller to report.
int runGame(const GameOptions& options);

} // namespace lpv::game
