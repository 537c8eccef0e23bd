// How close the engine's indirect light is to a path-traced reference of the same view: the
// figures the fidelity benchmark prints and the fidelity test bounds. Both images are linear
// radiance per pixel (the engine's render.debug_view=indirect, the reference's diffuse-indirect
// pass; or the fog's in-scattered light, render.debug_view=fog, and the reference's fog images);
// pixels without geometry in the reference are left out.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

namespace lpv::bench {

// The reference's per-pixel surface, to leave out the sky and sort pixels by orientation.
struct ReferenceSurfaces {
    std::span<const glm::vec3> normal; // world-space shading normal of the visible surface
    std::span<const uint8_t> hit;      // 1 where the pixel shows geometry
};

// Mean of the engine's over the reference's light on the pixels of one orientation; -1 when the
// view shows none of them (or the reference is black there).
struct OrientationRatios {
    float ceilings = -1.0f; // normal.y < -0.7
    float floors = -1.0f;   // normal.y > 0.7
    float walls = -1.0f;    // the rest
};

struct FidelityFigures {
    uint32_t pixels = 0;             // pixels with geometry
    glm::vec3 meanRatio{0.0f};       // per channel: engine mean / reference mean
    float relativeRmse = 0.0f;       // RMSE of luminance / mean reference luminance
    float bestScale = 1.0f;          // the single factor on the engine's image that minimises RMSE
    float relativeRmseScaled = 0.0f; // relativeRmse after that factor: the error in shape alone
    float referenceMean = 0.0f;      // the reference's mean luminance
    OrientationRatios orientation;
    float shareOver3x = 0.0f; // share of pixels whose luminance is over 3x the reference's
};

// `engine` and `reference` hold width x height pixels in the same order. A pixel counts as over 3x
// only where the engine's luminance also exceeds 1% of the reference's mean, so that noise on
// black reference pixels does not count.
FidelityFigures compareIndirect(std::span<const glm::vec3> engine, std::span<const glm::vec3> reference,
                                const ReferenceSurfaces& surfaces);

} // namespace lpv::bench
