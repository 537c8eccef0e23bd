// The engine's adapter for the GI's frame: what it reads of engine::Renderer, and one call that
// reads gi.* from the config and updates the GI, for a game built on the engine's renderer.
#pragma once

#include "engine/config/Config.h"
#include "engine/render/Renderer.h"
#include "gi/GiFrameInputs.h"
#include "gi/LightPropagationVolume.h"

namespace lpv::gi {

// The renderer's scene, lights, sun and specular table, seen from `camera`.
GiFrameInputs giFrameInputs(const engine::Renderer& renderer, const engine::CameraMatrices& camera);

// lpv.update(lpvSettingsFrom(config), giFrameInputs(renderer, camera), profiler): refused settings,
// those that contradict each other included, are a returned result, and the GI keeps what it ran.
[[nodiscard]] GiConfigResult updateFromConfig(LightPropagationVolume& lpv, const engine::Config& config,
                                              const engine::Renderer& renderer,
                                              const engine::CameraMatrices& camera,
                                              engine::FrameProfiler* profiler = nullptr);

} // namespace lpv::gi
