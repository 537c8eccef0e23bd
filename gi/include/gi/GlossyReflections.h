// Glossy reflections from the LPV (gi.glossy): a fullscreen pass that marches a few cells along
// each pixel's reflected view ray (the GGX lobe's mean direction) through the cascades and draws the radiance
// arriving along it (linear RGBA16F) over the lookup's reflection, for the lighting pass to add under the
// lobe's weight. The march and the roughness cone are in gi/shaders/lpv_glossy.glsl.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/IndirectLighting.h"
#include "gi/CascadeClasses.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <array>
#include <span>

namespace lpv::gi {

// One cascade as the march sees it.
struct GlossyCascade {
    VolumeGrid grid;
    std::array<rhi::TextureHandle, 3> sh; // R, G, B
};

class GlossyReflections {
public:
    // Cells marched per pixel: the talk's "4 cells is sufficient for moderately glossy objects".
    // lpv_glossy.glsl has it as GLOSSY_STEPS.
    static constexpr uint32_t kSteps = 4;

    explicit GlossyReflections(rhi::Device& device);
    ~GlossyReflections();
    GlossyReflections(const GlossyReflections&) = delete;
    GlossyReflections& operator=(const GlossyReflections&) = delete;

    // Draws the march over `target` (finest cascade first in `cascades`, 1 to 4 of them), which
    // holds the lookup's glossy radiance of the lobe's mean direction (the lobes from
    // `specularAlbedoTable`, engine::SpecularAlbedoTexture's table): premultiplied by the march's
    // share, its fade (gi.glossy_max_roughness: all of it up to 0.1 below `maxRoughness`, none from
    // it on, where the march does not run and the texel keeps the lookup's value). `rgba8Range` > 0:
    // the volumes are rgba8, encoded in gi.rgba8_range (a radiance; each cascade's range is it times
    // its cell area, LpvVolumes::encodeRange). `target` is 1/divisor of the G-buffer per axis: its texel
    // t marches from G-buffer pixel t x divisor. With `classes` (classified this frame for these
    // cascades and the target's size, glossy on) each cascade marches only its own glossy classes'
    // texels (CascadeClasses.h); only where CascadeClasses::wanted(device).
    void record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                const engine::GBufferView& gbuffer, std::span<const GlossyCascade> cascades, float rgba8Range,
                float maxRoughness, rhi::TextureHandle target, rhi::TextureHandle specularAlbedoTable,
                uint32_t divisor = 1, const CascadeClasses* classes = nullptr);

private:
    rhi::Device& device_;
    // By cascade count - 1: each march names its cascade's textures at compile time.
    std::array<rhi::GraphicsPipelineHandle, 4> pipelines_{};
    // By cascade, for a class draw (CascadeClasses::wanted only).
    std::array<rhi::GraphicsPipelineHandle, 4> classPipelines_{};
    rhi::SamplerHandle pointSampler_, linearSampler_;
};

// Depth, normal, albedo, the lobe table's two blocks, kSteps trilinear fetches of the three
// volumes, per pixel marched.
engine::WorkCounts glossyWork(uint64_t pixels);

} // namespace lpv::gi
