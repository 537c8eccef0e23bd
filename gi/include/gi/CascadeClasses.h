// Cascade classes: the lookup and the glossy march choose a cascade per texel (the finest whose
// usable region holds the point, blended into the next coarser one in a band at its border). A GPU
// skips the branches no lane of a wave takes; a device that runs both sides of every branch
// (rhi::Caps::maskedBranches: Mesa's llvmpipe and lavapipe) pays for every cascade at every texel.
// There a classification pass first stores each texel's class in a stencil, and the lookup and
// the glossy march draw once per cascade (the lookup also once per blend band), each draw's
// stencil test selecting its field of the class: such a device skips a block of texels that fails
// the test, so each texel runs one cascade's code.
//
// A class holds the lookup's cascade, whether the texel lies in its blend band, and the glossy
// march's cascade, which may be the next finer one (its rule tests the march's start, half a cell
// off the surface); gi/shaders/cascade_region.glsl holds the rules and the stencil layout,
// cascade_classify_body.glsl the classification. The stencil is exported by the classification's
// fragment shader (rhi::Caps::shaderStencilExport), so the classes cost one pass.
//
// Why stencil fields: the classes were first depths with an equal depth test, so each draw matched
// one combination of the lookup's and the march's classes (13 lookup and 8 glossy draws with 3
// cascades). On llvmpipe a fullscreen draw whose test fails everywhere still costs 0.5-0.8 ms at
// 1280x720's half resolution (13 empty draws added 6-10 ms to the atrium's lookup): the
// rasterizer visits every block. A draw that tests only its own field of the stencil makes it 5
// lookup and 3 glossy draws (interleaved runs: the lookup 5-6 ms and the march 2-4 ms faster).
#pragma once

#include "engine/render/CameraMatrices.h"
#include "engine/render/IndirectLighting.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <array>
#include <cstdint>
#include <span>

namespace lpv::gi {

class CascadeClasses {
public:
    explicit CascadeClasses(rhi::Device& device);
    ~CascadeClasses();
    CascadeClasses(const CascadeClasses&) = delete;
    CascadeClasses& operator=(const CascadeClasses&) = delete;

    // Whether `device` draws classes: it runs both sides of its branches and can export a stencil.
    static bool wanted(const rhi::Device& device);

    // Writes every texel's class into target(), made (or remade) at `width` x `height`, the lookup
    // target's size: texel t classifies G-buffer pixel t x divisor, as the lookup reads it.
    // `cascades`: finest first, 2 to 4; `blendBand`: the band's width as a fraction of a cascade's
    // half-extent; `glossyMaxRoughness`: the glossy march's (GlossyReflections::record), 0 when
    // there is no march.
    void record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                const engine::GBufferView& gbuffer, std::span<const VolumeGrid> cascades, float blendBand,
                float glossyMaxRoughness, uint32_t width, uint32_t height, uint32_t divisor);
    // The classes: a D32FS8 target whose stencil holds each lookup texel's class (sky: 0, which
    // no draw matches). Its depth is unused.
    rhi::TextureHandle target() const { return target_; }

    // A class draw's pipeline state, for a fullscreen triangle in a render pass with target() as
    // its (loaded) depth target: the lookup's texels in `cascade` (inside its blend band or not),
    // or the glossy march's texels in `cascade`.
    static void configureLookupDraw(rhi::GraphicsPipelineDesc& desc, uint32_t cascade, bool blend);
    static void configureGlossyDraw(rhi::GraphicsPipelineDesc& desc, uint32_t cascade);

private:
    rhi::Device& device_;
    rhi::TextureHandle target_;
    // By cascade count - 2: the classification for 2 to 4 cascades.
    std::array<rhi::GraphicsPipelineHandle, 3> pipelines_{};
    rhi::SamplerHandle pointSampler_;
};

// Binds what the lookup and the glossy march both read: the G-buffer's depth and normal at
// bindings 1 and 2 (`point`), and the cascades' volumes as lpv_cascades.glsl declares them
// (`linear`): cascade c's R, G, B at bindings 3 + 3c .. 5 + 3c, the bindings of cascades past the
// coarsest (`finestFirst`, 1 to 4) to the coarsest.
void bindCascadeReads(rhi::CommandList& cmd, const engine::GBufferView& gbuffer,
                      std::span<const std::array<rhi::TextureHandle, 3>> finestFirst,
                      rhi::SamplerHandle point, rhi::SamplerHandle linear);

} // namespace lpv::gi
