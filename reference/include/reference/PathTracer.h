// The path-traced ground truth the GI is measured against (issue 44): per pixel, for the engine's
// camera, the diffuse-indirect radiance (what render.debug_view=indirect shows), the direct diffuse
// radiance and their sum, plus the visible surface's position and normal. glTF's surfaces as the
// engine shows their diffuse part (RayScene.h), black sky, no emission or specular light;
// next-event estimation at every vertex, cosine-weighted bounces.
// With a medium (issue 48, fog): the light it scatters toward the camera, single scattering of the
// sun and of the surfaces' light, and the transmittance to the visible surface.
#pragma once

#include "reference/DirectLighting.h"
#include "reference/Medium.h"
#include "reference/RayScene.h"

#include "engine/scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace lpv::reference {

struct TraceSettings {
    uint32_t width = 256, height = 256;
    uint32_t samplesPerPixel = 256;
    uint32_t bounces = 1; // diffuse bounces in the indirect: 1 = light -> surface -> visible surface
    uint64_t seed = 1;
    uint32_t threads = 0;  // 0: all cores; the image does not depend on it
    bool progress = false; // a progress line on stderr
    // The camera rays' medium (density 0: none; the fog images are then 0 and the transmittance 1).
    // It changes no other image: surfaces are lit, and their light travels, as if it were absent.
    Medium medium;
    uint32_t mediumSamples = 4; // distance samples along each camera sample's ray
    // The surfaces' model where trace() builds the RayScene itself (RayScene::Surfaces).
    RayScene::Surfaces surfaces = RayScene::Surfaces::Gltf;
};

// Row 0 at the top, as the engine's images; linear radiance (RGB). position, normal and hit are
// those of the ray through each pixel's centre (hit = 0: sky, position and normal zero).
struct TracedImage {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> indirect, direct, combined, position, normal;
    std::vector<uint8_t> hit;
    // The medium along each pixel's rays from the camera to the visible surface (or where a missing
    // ray ends, see Medium), radiance arriving at the camera: the sun's single scattering, the
    // single scattering of light that bounced 1..bounces times off surfaces (what an LPV holds),
    // their sum, the transmittance (grey) and combined x transmittance + fog, what the camera sees.
    std::vector<glm::vec3> fogSun, fogIndirect, fog, transmittance, fogged;
};

// The scene's own lights (SceneLights).
TracedImage trace(const engine::Scene& scene, const engine::Camera& camera, const TraceSettings& settings);
// Any direct lighting, on a BVH the caller keeps (to render several views of one scene).
TracedImage trace(const RayScene& scene, const DirectLighting& lights, const engine::Camera& camera,
                  const TraceSettings& settings);

// The mean indirect irradiance at `p` (light that bounced 1..bounces times before arriving) over
// `samples` cosine-weighted paths, each times the share p's diffuse base reflects toward `toViewer`
// (SurfacePoint::diffuseShare): what trace() multiplies by albedo / pi for a visible surface.
glm::vec3 indirectIrradiance(const RayScene& scene, const DirectLighting& lights, const SurfacePoint& p,
                             glm::vec3 toViewer, uint32_t bounces, uint32_t samples, uint64_t seed);

// The medium along one ray, as a pixel of trace() sees it: radiance scattered toward `origin`, the
// transmittance from the first surface (or where a missing ray ends) and the distance to it.
struct MediumRadiance {
    glm::vec3 sun{0.0f}, indirect{0.0f};
    float transmittance = 1.0f;
    float distance = 0.0f;
};
MediumRadiance scatteredAlongRay(const RayScene& scene, const DirectLighting& lights, const Medium& medium,
                                 glm::vec3 origin, glm::vec3 direction, uint32_t bounces, uint32_t samples,
                                 uint64_t seed);

} // namespace lpv::reference
