// Spherical harmonics of order 1 (4 coefficients), the representation of radiant intensity in
// every LPV cell, one set per colour channel. Coefficient order: Y00, Y1-1 (y), Y10 (z), Y11 (x),
// without the Condon-Shortley sign (../shared/docs/lpv-notes.md, "SH L1 constants").
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace lpv::gi {

inline constexpr float kShY0 = 0.282094792f; // 1 / (2 sqrt(pi))
inline constexpr float kShY1 = 0.488602512f; // sqrt(3) / (2 sqrt(pi))
// Projection of the clamped cosine lobe max(0, dot(n, w)) onto the basis.
inline constexpr float kCosLobeC0 = 0.886226925f; // sqrt(pi) / 2
inline constexpr float kCosLobeC1 = 1.023326708f; // sqrt(pi / 3)
inline constexpr float kPi = 3.14159265358979f;

// The basis functions evaluated in direction `w` (unit).
inline glm::vec4 shBasis(glm::vec3 w) {
    return {kShY0, kShY1 * w.y, kShY1 * w.z, kShY1 * w.x};
}

// The clamped cosine lobe around unit `n`.
inline glm::vec4 shCosineLobe(glm::vec3 n) {
    return {kCosLobeC0, kCosLobeC1 * n.y, kCosLobeC1 * n.z, kCosLobeC1 * n.x};
}

// The function with coefficients `sh` evaluated in direction `w`.
inline float shEvaluate(const glm::vec4& sh, glm::vec3 w) {
    return glm::dot(sh, shBasis(w));
}

// Irradiance at a surface with normal n: the integral of the function against the clamped cosine
// lobe around n, which by orthonormality is the dot product of the two coefficient sets.
inline float shIrradiance(const glm::vec4& sh, glm::vec3 n) {
    return glm::dot(sh, shCosineLobe(n));
}

} // namespace lpv::gi
