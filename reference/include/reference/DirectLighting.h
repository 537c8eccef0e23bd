// Where direct light comes from in the path tracer: the irradiance a surface point receives straight
// from the light sources, shadowed. The scene's own lights are one implementation (SceneLights);
// tests give surfaces a known irradiance instead, so closed forms can check the bounces.
#pragma once

#include "reference/RayScene.h"

#include "engine/scene/Scene.h"

#include <glm/vec3.hpp>

#include <optional>
#include <vector>

namespace lpv::reference {

// A directional light: what a medium scatters toward the camera directly (see Medium.h).
struct Sun {
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // unit, where the light travels
    glm::vec3 irradiance{0.0f};             // on a surface facing it, unshadowed
};

class DirectLighting {
public:
    virtual ~DirectLighting() = default;
    // Irradiance (W/m^2 per channel, cosine included) arriving directly at `p` on the side its
    // normal faces, each light's times the share p's diffuse base reflects toward `toViewer` (unit,
    // away from the surface: SurfacePoint::diffuseShare); shadow rays through `scene`. Called from
    // many threads at once.
    virtual glm::vec3 irradiance(const SurfacePoint& p, const RayScene& scene, glm::vec3 toViewer) const = 0;
    // The sun whose single scattering a medium adds, if any.
    virtual std::optional<Sun> sun() const { return std::nullopt; }
};

// The engine's lights with the engine's units and falloffs (engine/shaders/lighting_body.glsl):
// - the first directional light (the renderer's sun; it ignores any others): intensity x color is
//   the irradiance on a surface facing it, travelling along `direction`;
// - point and spot lights: intensity x color is radiant intensity (W/sr), E = I cos / d^2 times
//   clamp(1 - (d/range)^4, 0, 1) when range > 0; spots times
//   smoothstep(cos(outer), cos(inner), dot(-toLight, direction)).
// The cosine is the shading normal's; every light casts a shadow ray.
class SceneLights : public DirectLighting {
public:
    explicit SceneLights(const engine::Scene& scene);
    glm::vec3 irradiance(const SurfacePoint& p, const RayScene& scene, glm::vec3 toViewer) const override;
    std::optional<Sun> sun() const override;

private:
    struct Punctual {
        glm::vec3 position, direction, intensity;
        float range, cosOuter, cosInner;
        bool spot;
    };
    bool hasSun_ = false;
    glm::vec3 sunDirection_{0.0f, -1.0f, 0.0f}; // where the light travels
    glm::vec3 sunIrradiance_{0.0f};
    std::vector<Punctual> punctual_;
};

} // namespace lpv::reference
