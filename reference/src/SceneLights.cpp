// The engine's lights as direct irradiance: lighting_body.glsl's sun term and punctualArrival(),
// with shadow rays where the engine has shadow maps, and what the diffuse base keeps of each.
#include "reference/DirectLighting.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::reference {
namespace {

float smoothstep(float edge0, float edge1, float x) {
    // GLSL's definition; equal edges (inner = outer cone) are undefined there: a hard edge here.
    if (edge0 == edge1) return x < edge0 ? 0.0f : 1.0f;
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

} // namespace

SceneLights::SceneLights(const engine::Scene& scene) {
    for (const engine::Light& l : scene.lights) {
        if (l.type == engine::LightType::Directional) {
            // Renderer::setScene takes the first directional light as its sun and ignores the rest.
            if (hasSun_) continue;
            hasSun_ = true;
            sunDirection_ = glm::normalize(l.direction);
            sunIrradiance_ = l.color * l.intensity;
            continue;
        }
        punctual_.push_back({l.position, glm::normalize(l.direction), l.color * l.intensity, l.range,
                             std::cos(l.outerConeAngle), std::cos(l.innerConeAngle),
                             l.type == engine::LightType::Spot});
    }
}

std::optional<Sun> SceneLights::sun() const {
    if (!hasSun_) return std::nullopt;
    return Sun{sunDirection_, sunIrradiance_};
}

glm::vec3 SceneLights::irradiance(const SurfacePoint& p, const RayScene& scene, glm::vec3 toViewer) const {
    glm::vec3 e(0.0f);
    if (hasSun_) {
        const glm::vec3 toLight = -sunDirection_;
        const float cosine = glm::dot(p.normal, toLight);
        // A light behind the geometric surface cannot reach this side, whatever the shading normal.
        if (cosine > 0.0f && glm::dot(p.geometricNormal, toLight) > 0.0f && !scene.occluded(p, toLight))
            e += sunIrradiance_ * cosine * p.diffuseShare(toLight, toViewer);
    }
    for (const Punctual& l : punctual_) {
        const glm::vec3 toLight = l.position - p.position;
        const float d2 = std::max(glm::dot(toLight, toLight), 1e-4f); // the shader's clamp
        const float d = std::sqrt(d2);
        const glm::vec3 dir = toLight / d;
        const float cosine = glm::dot(p.normal, dir);
        if (cosine <= 0.0f || glm::dot(p.geometricNormal, dir) <= 0.0f) continue;
        float attenuation = 1.0f / d2;
        if (l.range > 0.0f) {
            const float ratio = d / l.range;
            attenuation *= std::clamp(1.0f - ratio * ratio * ratio * ratio, 0.0f, 1.0f);
        }
        if (l.spot) attenuation *= smoothstep(l.cosOuter, l.cosInner, glm::dot(-dir, l.direction));
        if (attenuation <= 0.0f || scene.occluded(p, dir, d)) continue;
        e += l.intensity * attenuation * cosine * p.diffuseShare(dir, toViewer);
    }
    return e;
}

} // namespace lpv::reference
