// The participating medium of the reference (issue 48, fog): the engine's fog.* settings as a plain
// struct, and the closed forms the estimator and the tests share: Henyey-Greenstein scattering,
// optical depth and transmittance of a homogeneous or exponential height fog, and distances drawn in
// proportion to sigma_t x transmittance (free-flight sampling, exact for both profiles).
#pragma once

#include <glm/vec3.hpp>

#include <limits>

namespace lpv::reference {

// The engine's fog.* settings (gi::FogSettings), with their defaults: sigma_t(y) = density x
// exp(-heightFalloff x max(y - baseHeight, 0)) per metre, grey (constant at and below the base
// height); the scattering coefficient is albedo x sigma_t per channel (the rest is absorbed).
struct Medium {
    float density = 0.0f;       // sigma_t at and below baseHeight (1/m); 0: no medium, nothing is computed
    glm::vec3 albedo{0.9f};     // single-scattering albedo sigma_s / sigma_t
    float heightFalloff = 0.0f; // 1/m; 0: homogeneous
    float baseHeight = 0.0f;    // m
    float anisotropy = 0.2f;    // Henyey-Greenstein g, in (-1, 1); > 0 scatters forward
    // Where a camera ray that meets no surface stops: after missDistance (m; the physical answer is
    // infinity), or, with missAtSceneBounds, where it leaves engine::Scene::bounds, as the engine's
    // march does (nothing there when the camera looks past the scene from outside its bounds).
    float missDistance = std::numeric_limits<float>::infinity();
    bool missAtSceneBounds = false;
    // Whether the sun's light is attenuated by the medium on its way to a scattering point. Off, as
    // in the engine, whose sun reaches fog and surfaces alike through its shadow map only.
    bool attenuateSunlight = false;

    bool present() const { return density > 0.0f; }
};

// The Henyey-Greenstein phase function (1/sr): cosTheta is between the direction the light travels
// before and after scattering. Integrates to 1 over the sphere.
float henyeyGreenstein(float cosTheta, float g);
// A direction whose cosine with the unit `incident` (the direction light travels before scattering)
// has the density henyeyGreenstein(cos, g); u1, u2 uniform in [0, 1).
glm::vec3 sampleHenyeyGreenstein(glm::vec3 incident, float g, float u1, float u2);

// sigma_t at a point (1/m).
float extinction(const Medium& medium, glm::vec3 position);
// The integral of sigma_t from `origin` over `distance` along the unit `direction` (closed form; may
// be infinite, e.g. a homogeneous medium over an infinite distance).
double opticalDepth(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double distance);
// exp(-opticalDepth).
float transmittance(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double distance);
// The distance t in [0, maxDistance] where 1 - T(t) = u (1 - T(maxDistance)): drawn with u uniform,
// its density is sigma_t(t) T(t) / (1 - T(maxDistance)). Needs 1 - T(maxDistance) > 0.
float sampleDistance(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double maxDistance,
                     float u);

} // namespace lpv::reference
