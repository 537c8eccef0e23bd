// The engine's fog for one view, as the fidelity benchmark compares it with the path tracer's
// medium: render.debug_view=fog (the radiance the fog scatters toward the camera alone, linear),
// fog.resolution=full so that the figures are the march's and not the upsampling's, the medium
// given as the reference's reference::Medium (the engine's fog.* settings as a plain struct).
#pragma once

#include "engine/config/Config.h"
#include "engine/scene/Scene.h"
#include "reference/Medium.h"
#include "rhi/Device.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lpv::bench {

// fog.enabled=true and the medium's fog.density, fog.albedo, fog.height_falloff, fog.base_height
// and fog.anisotropy. The engine's march always stops rays that meet nothing at the scene's bounds
// and never attenuates the sun: the reference matches it with missAtSceneBounds and
// attenuateSunlight off.
std::vector<std::string> fogAssignments(const reference::Medium& medium);

// renderEngineFrame (EngineIndirect.h) with `config` plus fogAssignments(medium),
// render.debug_view=fog and fog.resolution=full: the last frame's in-scattered radiance. With
// gi.enabled=false in `config` the sun alone lights the fog.
std::vector<glm::vec3> renderEngineFog(rhi::Device& device, const engine::Scene& scene,
                                       const engine::Camera& camera, uint32_t width, uint32_t height,
                                       engine::Config config, const reference::Medium& medium,
                                       int frames = 3);

// The fog split as the reference splits it (TracedImage::fogSun, fogIndirect).
struct EngineFogParts {
    std::vector<glm::vec3> total;    // GI as `config` says
    std::vector<glm::vec3> sun;      // gi.enabled=false: the sun through its shadow map alone
    std::vector<glm::vec3> indirect; // total - sun: the LPV's light scattered toward the camera
};

// Two renders, `config` as it is and with gi.enabled=false. The march's jitter is fixed per pixel
// and the sun's shadow map does not depend on the GI, so the difference is the LPV's term alone.
EngineFogParts renderEngineFogParts(rhi::Device& device, const engine::Scene& scene,
                                    const engine::Camera& camera, uint32_t width, uint32_t height,
                                    const engine::Config& config, const reference::Medium& medium,
                                    int frames = 3);

} // namespace lpv::bench
