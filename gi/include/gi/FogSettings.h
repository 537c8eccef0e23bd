// The participating medium's settings (fog.*), a plain struct inside LpvSettings: an exponential
// height fog of single-scattering albedo `albedo`, lit by the sun through its shadow map and by the
// LPV's indirect light. The engine's adapter (gi/adapter/LpvConfig.h) reads them from fog.*.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>

namespace lpv::gi {

struct FogSettings {
    bool enabled = false;
    // Extinction per metre at and below baseHeight; above it the medium thins by
    // exp(-heightFalloff x height above baseHeight). heightFalloff 0: homogeneous.
    float density = 0.02f;
    glm::vec3 albedo{0.9f}; // scattering over extinction, per channel
    float heightFalloff = 0.0f;
    float baseHeight = 0.0f;
    float anisotropy = 0.2f; // Henyey-Greenstein g: 0 isotropic, > 0 forward scattering
    // Per axis, 1/resolutionDivisor of the frame's pixels march (full 1, half 2, quarter 4); the
    // lighting pass rebuilds the rest with a depth-aware filter.
    uint32_t resolutionDivisor = 2;
    uint32_t steps = 24; // march steps per ray
    bool operator==(const FogSettings&) const = default;
};

} // namespace lpv::gi
