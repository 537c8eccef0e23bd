// Cascade classes: the lookup and the glossy march choose a cascade per texel (the finest whose
// usable region holds the point, blended into the next coarser one in a band at its border). A GPU
// skips the branches no lane of a wave takes; a device that runs both sides of every branch
// (rhi::Caps::maskedBranches: Mesa's llvmpipe and lavapipe) pays for every cascade at every texel.
// There a classification pass first stores each texel's class as a depth, and the lookup and the
// glossy march draw once per class, at that class's depth with an equal depth test: such a device
// skips a block of texels that fails the depth test, so each texel runs one class's code.
//
// A class is the lookup's cascade, whether the texel lies in its blend band, and the glossy
// march's cascade, which may be the next finer one (its rule tests the march's start, half a cell
// off the surface); gi/shaders/cascade_region.glsl holds the rules and the depths,
// cascade_classify.frag the classification.
#pragma once

#include "engine/render/CameraMatrices.h"
#include "engine/render/IndirectLighting.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <array>
#include <cstdint>
#include <span>

namespace lpv::gi {

// Which cascade the glossy march of a texel runs in.
enum class GlossyMarch : uint32_t {
    None,  // none: gi.glossy off, the sky, or a fully rough surface
    Same,  // the lookup's cascade
    Finer, // the next finer one
};

struct CascadeClass {
    uint32_t cascade = 0; // the lookup's
    bool blend = false;   // in the cascade's blend band: the next coarser one takes a share
    GlossyMarch glossy = GlossyMarch::None;
    // As cascadeClassDepth's k in cascade_region.glsl.
    uint32_t index() const { return 6 * cascade + (blend ? 3 : 0) + uint32_t(glossy); }
};

class CascadeClasses {
public:
    explicit CascadeClasses(rhi::Device& device);
    ~CascadeClasses();
    CascadeClasses(const CascadeClasses&) = delete;
    CascadeClasses& operator=(const CascadeClasses&) = delete;

    // Writes every texel's class into depth(), made (or remade) at `width` x `height`, the lookup
    // target's size: texel t classifies G-buffer pixel t x divisor, as the lookup reads it.
    // `cascades`: finest first, 2 to 4; `blendBand`: the band's width as a fraction of a cascade's
    // half-extent.
    void classify(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                  const engine::GBufferView& gbuffer, std::span<const VolumeGrid> cascades, float blendBand,
                  bool glossy, uint32_t width, uint32_t height, uint32_t divisor);
    // The classes: one D32F texel per lookup texel (sky: 1, which no class draw matches).
    rhi::TextureHandle depth() const { return depth_; }

    // A class draw's pipeline: the class vertex shader and an equal depth test against depth().
    static void configureClassDraw(rhi::GraphicsPipelineDesc& desc);
    // Class `k`'s fullscreen triangle, in a render pass with depth() as its (loaded) depth target.
    static void drawClass(rhi::CommandList& cmd, const CascadeClass& k) { cmd.draw(3, 1, 3 * k.index()); }

private:
    rhi::Device& device_;
    rhi::TextureHandle depth_;
    rhi::GraphicsPipelineHandle pipeline_;
    rhi::SamplerHandle pointSampler_;
};

// Binds the cascades' volumes as lpv_cascades.glsl declares them for the lookup and the glossy
// march: cascade c's R, G, B at bindings 3 + 3c .. 5 + 3c, the bindings of cascades past the
// coarsest (`finestFirst`, 1 to 4) to the coarsest.
void bindCascadeVolumes(rhi::CommandList& cmd, std::span<const std::array<rhi::TextureHandle, 3>> finestFirst,
                        rhi::SamplerHandle sampler);

} // namespace lpv::gi
