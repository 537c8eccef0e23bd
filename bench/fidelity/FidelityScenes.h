// The scenes the fidelity benchmark and test compare with the path tracer, each with the view and
// the GI settings it is judged at (the finest cascade sized to the room), and the fog comparison's
// medium (issue 48).
#pragma once

#include "reference/Medium.h"

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
    // The reference's samples per pixel are this times the benchmark's: the built-in box's bounced
    // light all comes from one small sunlit patch, and at the others' count its noise would be
    // half its relative RMSE (docs/gi-fidelity.md).
    uint32_t sampleFactor = 1;
};

// Every scene, glTF paths under `sceneDir` (bench/scenes in the source tree).
std::vector<FidelityScene> fidelityScenes(const std::string& sceneDir);
// Their names, for --scenes.
std::vector<std::string> fidelitySceneNames();

// The fog comparison: the engine's fog (EngineFog.h) against the reference's medium in one of the
// scenes above, with that scene's GI settings, at a smaller size (the indirect part is noisy).
struct FidelityFog {
    std::string scene;        // a FidelityScene's name
    reference::Medium medium; // missAtSceneBounds on, as the engine's march
    uint32_t width = 128, height = 128;
};
FidelityFog fidelityFog();

} // namespace lpv::bench
