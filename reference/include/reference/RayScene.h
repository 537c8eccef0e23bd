// An engine::Scene as the path tracer sees it: every instance's triangles in world space in one
// Embree 3 BVH, with each triangle's material found at the hit point: glTF's metallic-roughness
// model as the engine's lighting pass shows its diffuse part, a Lambertian base (base colour factor x
// texture x (1 - metallic)) under a specular layer that keeps 1 - F of the light (fresnel_mix); the
// layer's own reflection is left out, as the reference leaves out specular light.
#pragma once

#include "engine/scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace lpv::reference {

// A point on a surface, seen from one side: both normals face the side the ray came from.
struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};          // shading: the interpolated vertex normal
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f}; // the triangle's; rays leave offset along it
    glm::vec3 albedo{0.0f};                      // linear diffuse reflectance
    // glTF's specular layer over the base: its reflectance at normal incidence (4% for a
    // dielectric, the base colour for a metal). None on a plain Lambertian surface.
    bool layered = false;
    glm::vec3 f0{0.0f};
    uint32_t instance = 0; // index into Scene::instances

    // The share of the light arriving from `toLight` that the base reflects toward `toViewer` (unit
    // vectors, away from the surface): 1 - F(toViewer . h), Schlick's F at the half vector h, as
    // glTF's fresnel_mix and the engine's lighting pass (responseTo) have it; 1 without a layer.
    glm::vec3 diffuseShare(glm::vec3 toLight, glm::vec3 toViewer) const;
};

class RayScene {
public:
    // The surfaces' model: glTF's (a specular layer over a Lambertian base), or plain Lambertian
    // surfaces of the same albedo (closed forms assume them).
    enum class Surfaces { Gltf, Lambertian };
    // The tools' --surfaces choices (lpv_reference, lpv_fidelity), each with its model, and their help.
    static const std::map<std::string, Surfaces>& surfaceNames();
    static constexpr const char* kSurfacesHelp =
        "The reference's surfaces: gltf (a Lambertian base under glTF's specular layer, as the engine shows "
        "it) or lambertian (the base alone)";

    // Builds the BVH (Embree's robust mode; triangles are two-sided). Throws std::runtime_error if
    // Embree fails.
    explicit RayScene(const engine::Scene& scene, Surfaces surfaces = Surfaces::Gltf);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    // The nearest surface along the ray within (0, maxDistance], or nothing (the sky).
    std::optional<SurfacePoint> intersect(glm::vec3 origin, glm::vec3 direction,
                                          float maxDistance = std::numeric_limits<float>::infinity()) const;
    // Whether anything lies between `from` (offset off its surface) and `distance` along the unit
    // `direction`; the far end is shortened by the same offset so a light on a surface still counts.
    bool occluded(const SurfacePoint& from, glm::vec3 direction,
                  float distance = std::numeric_limits<float>::infinity()) const;
    // The same from a point off any surface (in a medium): no offset at either end.
    bool occluded(glm::vec3 origin, glm::vec3 direction,
                  float distance = std::numeric_limits<float>::infinity()) const;
    // The scene's world bounds (engine::Scene::bounds, of all instances).
    const engine::Bounds& bounds() const;
    // Where a ray leaving `from` toward `direction`'s side of its surface starts.
    glm::vec3 rayOrigin(const SurfacePoint& from, glm::vec3 direction) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace lpv::reference
