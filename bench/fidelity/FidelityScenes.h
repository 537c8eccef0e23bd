// The scenes the fidelity benchmark and test compare with the path tracer, each with the view and
// the GI settings it is judged at (the finest cascade sized to the room).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lpv::bench {

struct FidelityScene {
    std::string name;                  // as printed, and the stem of the images written
    std::string source;                // a built-in scene name or a glTF path
    std::vector<std::string> settings; // gi.* assignments for this scene, before the caller's --set
    uint32_t width = 256, height = 256;
    bool targets = false; // a Cornell-type scene: the fidelity targets apply (else figures only)
};

// Every scene, glTF paths under `sceneDir` (bench/scenes in the source tree).
std::vector<FidelityScene> fidelityScenes(const std::string& sceneDir);
// Their names, for --scenes.
std::vector<std::string> fidelitySceneNames();

} // namespace lpv::bench
