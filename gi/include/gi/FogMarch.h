// Participating media lit by the LPV (Kaplanyan & Dachsbacher 2010, "participating media"): per
// texel a ray march from the camera to the surface (or out of the scene) through an exponential
// height fog, accumulating with transmittance the sun's single scattering through its shadow map
// (light shafts) and the LPV's indirect radiance weighted by the Henyey-Greenstein phase function.
// Writes what engine::IndirectLighting::renderMedium asks for: in-scattered radiance and
// transmittance. The march is gi/shaders/fog_march.glsl.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/IndirectLighting.h"
#include "engine/scene/Scene.h"
#include "gi/FogSettings.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <array>
#include <span>

namespace lpv::gi {

// One cascade's result as the march reads it: intensity SH per channel, finest first.
struct FogCascade {
    VolumeGrid grid;
    std::array<rhi::TextureHandle, 3> sh; // R, G, B
};

struct FogInputs {
    engine::CameraMatrices camera;
    engine::GBufferView gbuffer; // depth only
    engine::SunShadowView sun;
    // Finest first, up to 4; none: the sun alone (GI off or not made yet).
    std::span<const FogCascade> cascades;
    float rgba8Range = 0.0f; // > 0: the volumes are rgba8, encoded in gi.rgba8_range
    // Where a ray that meets no surface stops: beyond the scene there is nothing to light the fog.
    engine::Bounds sceneBounds;
};

class FogMarch {
public:
    explicit FogMarch(rhi::Device& device);
    ~FogMarch();
    FogMarch(const FogMarch&) = delete;
    FogMarch& operator=(const FogMarch&) = delete;

    // Marches every texel of `target` (RGBA16F, 1/settings.resolutionDivisor of the G-buffer per
    // axis; texel t for G-buffer pixel t x divisor) and writes in-scattered radiance (rgb) and
    // transmittance (a). The steps are jittered per pixel with a fixed pattern: no shimmer while
    // the camera stands still.
    void record(rhi::CommandList& cmd, const FogSettings& settings, const FogInputs& inputs,
                rhi::TextureHandle target);

private:
    rhi::Device& device_;
    // By cascade count (0: the sun alone): each names its cascades' textures at compile time.
    std::array<rhi::GraphicsPipelineHandle, 5> pipelines_{};
    rhi::SamplerHandle pointSampler_, linearSampler_, shadowSampler_;
};

// Per texel marched: the depth, then per step the density, a shadow compare and one trilinear fetch
// of the three volumes of the cascade holding the step.
engine::WorkCounts fogWork(const FogSettings& settings, uint64_t texels, bool indirect);

} // namespace lpv::gi
