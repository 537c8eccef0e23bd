// The lighting pass's direct light written out on the CPU, for the tests that check it. The
// specular: GGX D, Smith-Schlick G (k = alpha / 2), Schlick F (F0 4% for dielectrics), over
// 4 n.l n.v, with the lobe kept at roughness 0.1 or more as lighting_body.glsl keeps it. Times the
// irradiance (which holds n.l) it gives the reflected radiance. The diffuse base under it keeps
// 1 - F of the irradiance (glTF's fresnel_mix).
#pragma once

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lpv::test {

inline float schlickFresnel(float f0, float cosAngle) {
    return f0 + (1.0f - f0) * std::pow(1.0f - std::clamp(cosAngle, 0.0f, 1.0f), 5.0f);
}

inline float specularLobe(glm::vec3 n, glm::vec3 toEye, glm::vec3 toLight, float roughness,
                          float f0 = 0.04f) {
    const glm::vec3 v = glm::normalize(toEye), l = glm::normalize(toLight), h = glm::normalize(l + v);
    const float r = std::max(roughness, 0.1f), alpha = r * r, a2 = alpha * alpha, k = alpha / 2.0f;
    const float nl = glm::dot(n, l), nv = glm::dot(n, v), nh = glm::dot(n, h), vh = glm::dot(v, h);
    if (nl <= 0.0f || nv <= 0.0f) return 0.0f;
    const float denom = nh * nh * (a2 - 1.0f) + 1.0f;
    const float d = a2 / (std::numbers::pi_v<float> * denom * denom);
    const float g = nl / (nl * (1.0f - k) + k) * nv / (nv * (1.0f - k) + k);
    return d * g * schlickFresnel(f0, vh) / (4.0f * nl * nv);
}

// The share of a light's irradiance the diffuse base keeps: 1 - F at the half vector.
inline float diffuseShare(glm::vec3 toEye, glm::vec3 toLight, float f0 = 0.04f) {
    const glm::vec3 v = glm::normalize(toEye), h = glm::normalize(glm::normalize(toLight) + v);
    return 1.0f - schlickFresnel(f0, glm::dot(v, h));
}

} // namespace lpv::test
