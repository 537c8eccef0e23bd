// The indirect light's lookup (lpv_lookup.glsl): a fullscreen pass in which each texel reads its
// G-buffer pixel, picks the finest cascade that holds it (blended into the next coarser one in a
// band at its border) and samples the SH volumes half a cell along the normal. It writes the
// irradiance against the clamped cosine, with anisotropic damping, for the lighting pass to add,
// and the radiance of the glossy lobe's mean direction, which the glossy march then draws over
// (GlossyReflections).
#pragma once

#include "engine/render/CameraMatrices.h"
#include "engine/render/IndirectLighting.h"
#include "gi/CascadeClasses.h"
#include "gi/LpvReference.h"
#include "gi/VplGather.h"
#include "rhi/Device.h"

#include <array>
#include <cstdint>
#include <span>

namespace lpv::gi {

// One cascade as the lookup reads it.
struct LookupCascade {
    VolumeGrid grid;
    std::array<rhi::TextureHandle, 3> sh; // R, G, B
    // Its geometry volume's face transmittance (none without gi.occlusion), and whether the lookup
    // keeps to the faces it leaves open (lpv_lookup.glsl's keptInside): only where they were built
    // for this cascade, else it filters plainly.
    rhi::TextureHandle faces;
    bool keptToFaces = false;
};

// The settings the lookup reads, as plain values.
struct LookupOptions {
    float intensity = 1.0f; // gi.intensity
    // > 0: the volumes are rgba8, encoded in gi.rgba8_range (a radiance: the shader takes each
    // cascade's range from its cell size, LpvVolumes::encodeRange).
    float rgba8Range = 0.0f;
    bool damping = true; // gi.damping
    // The glossy target gets the lobe's mean direction (gi.glossy), else the cosine lobe around n.
    bool glossyLobe = false;
    // The blend band's width, as a fraction of a cascade's half-extent.
    float blendBand = 0.25f;
    // The targets are 1/divisor of the G-buffer per axis: texel t looks up G-buffer pixel t x divisor.
    uint32_t divisor = 1;
};

// gi.gather (gi/VplGather.h): the gathered cascades' first bounce kept apart from their light
// (each 3 SH textures like the light; a cascade that does not exist binds another's, unread) and
// the gathered light that replaces it.
struct LookupGather {
    std::array<std::array<rhi::TextureHandle, 3>, VplGather::kCascades> first{};
    rhi::TextureHandle gathered;
};

class IndirectLookup {
public:
    // lpv_lookup.glsl samples the G-buffer, every cascade's volumes and faces and the lobes' table in
    // one fragment shader: a device that binds too few textures there is refused with rhi::Error
    // saying so, not with a driver's failure to build the pipeline.
    explicit IndirectLookup(rhi::Device& device);
    ~IndirectLookup();
    IndirectLookup(const IndirectLookup&) = delete;
    IndirectLookup& operator=(const IndirectLookup&) = delete;

    // Writes `target` (irradiance) and `glossyTarget` (RGBA16F both) from `cascades`, finest first,
    // 1 to 4 of them; `specularAlbedoTable` is engine::SpecularAlbedoTexture's. With `classes`
    // (classified this frame for these cascades and the targets' size) each cascade draws only its
    // own classes' texels and the sky's are cleared (CascadeClasses.h); only where
    // CascadeClasses::wanted(device).
    void record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                const engine::GBufferView& gbuffer, std::span<const LookupCascade> cascades,
                const LookupOptions& options, rhi::TextureHandle target, rhi::TextureHandle glossyTarget,
                rhi::TextureHandle specularAlbedoTable, const CascadeClasses* classes = nullptr,
                const LookupGather* gather = nullptr);

    // Makes the lookups that take a gather (once; before a record() with one). Throws rhi::Error
    // where the device binds fewer fragment textures than kGatherTextureBindings.
    void enableGather();
    // What a lookup with a gather binds: the first bounces from 21, 3 a gathered cascade, then the
    // gather (lpv_lookup.glsl).
    static constexpr uint32_t kGatherTextureBindings = 21 + 3 * VplGather::kCascades + 1;

private:
    rhi::Device& device_;
    // By cascade count - 1: each lookup names its cascades' textures at compile time.
    std::array<rhi::GraphicsPipelineHandle, 4> pipelines_{};
    // By cascade and [interior, blend band], for a class draw (CascadeClasses::wanted only); the
    // coarsest cascade has no band.
    std::array<std::array<rhi::GraphicsPipelineHandle, 2>, 4> classPipelines_{};
    // The same with a gather (enableGather): by cascade count - 1, and for the classes of the
    // gathered cascades (a coarser class takes none).
    std::array<rhi::GraphicsPipelineHandle, 4> gatherPipelines_{};
    std::array<std::array<rhi::GraphicsPipelineHandle, 2>, VplGather::kCascades> gatherClassPipelines_{};
    rhi::SamplerHandle pointSampler_, linearSampler_;
};

} // namespace lpv::gi
