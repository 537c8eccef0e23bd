// The engine's indirect light for one view, as the fidelity benchmark compares it with the path
// tracer: the deferred renderer with the LPV, render.debug_view=indirect (albedo x indirect
// irradiance / pi, linear), SSAO off, read back as floats.
#pragma once

#include "engine/config/Config.h"
#include "engine/scene/Scene.h"
#include "rhi/Device.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace lpv::bench {

// Renders `frames` frames of `scene` from `camera` at width x height with `config` as it is (the
// LPV as the renderer's indirect light, GI on or off as `config` says) and returns the last HDR
// frame, row 0 at the top. Throws what the GI throws for a configuration the pc profile refuses.
std::vector<glm::vec3> renderEngineFrame(rhi::Device& device, const engine::Scene& scene,
                                         const engine::Camera& camera, uint32_t width, uint32_t height,
                                         const engine::Config& config, int frames = 3);

// renderEngineFrame with `config` (GI settings) plus render.debug_view=indirect and SSAO off: the
// last frame's indirect radiance.
std::vector<glm::vec3> renderEngineIndirect(rhi::Device& device, const engine::Scene& scene,
                                            const engine::Camera& camera, uint32_t width, uint32_t height,
                                            engine::Config config, int frames = 3);

} // namespace lpv::bench
