// What the GI reads of the game's frame, handed to LightPropagationVolume::update() each frame:
// plain data and handles the caller owns, so the GI needs no renderer of its own. Everything here
// must stay valid until that frame's renderIndirect() has run.
#pragma once

#include "engine/render/CameraMatrices.h"
#include "engine/render/GpuScene.h"
#include "engine/scene/Scene.h"
#include "rhi/Handle.h"

#include <glm/vec3.hpp>

#include <span>

namespace lpv::gi {

struct GiFrameInputs {
    engine::CameraMatrices camera;
    // The volume stays inside them (placeVolume); gi.cell_size = auto falls back to their size.
    engine::Bounds sceneBounds;
    // The scene's point and spot lights: the volume carries them (gi.analytic_lights) or their
    // bounce (gi.light_rsms, gi.point_light_rsms).
    std::span<const engine::Light> punctualLights;
    // The uploaded scene the reflective shadow maps are drawn from; null: the GI writes no light.
    const engine::GpuScene* scene = nullptr;
    glm::vec3 sunDirection{0.0f, -1.0f, 0.0f}; // where the sun's light travels
    glm::vec3 sunRadiance{0.0f};               // irradiance on a surface facing the sun
    // engine/render/SpecularAlbedo.h's table (engine::SpecularAlbedoTexture), which the lookup and
    // the glossy march weigh their lobes with, as the lighting pass does.
    rhi::TextureHandle specularAlbedo;
};

} // namespace lpv::gi
