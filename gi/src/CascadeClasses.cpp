// The cascade classification pass and the pipeline state of a class draw.
#include "gi/CascadeClasses.h"

#include "GiShaders.h"

#include "EngineShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace lpv::gi {
namespace {

// std140 block `Classify` of cascade_classify_body.glsl.
struct ClassifyUniforms {
    glm::mat4 invViewProjection;
    glm::vec4 gridOrigin[4];
    glm::ivec4 grid;
    glm::vec4 band;
    glm::ivec4 pixels;
};

// The stencil fields, as cascadeClassStencil in cascade_region.glsl writes them: bits 0-1 the
// lookup's cascade, bit 2 its blend band, bit 3 set on every looked-up texel (the sky's 0 matches
// no draw); bits 4-5 the glossy march's cascade, bit 6 set where it marches.
constexpr uint8_t kLookupField = 0x0f;
constexpr uint8_t kLookedUp = 0x08;
constexpr uint8_t kGlossyField = 0x70;
constexpr uint8_t kMarched = 0x40;

void configureClassDraw(rhi::GraphicsPipelineDesc& desc, uint8_t field, uint8_t value) {
    desc.vertex = &engine::shaders::fullscreen_vert;
    desc.depthTest = false;
    desc.depthWrite = false;
    desc.depthFormat = rhi::Format::D32FS8;
    desc.stencil = {true, rhi::CompareOp::Equal, value, field, 0, rhi::StencilOp::Keep};
}

} // namespace

CascadeClasses::CascadeClasses(rhi::Device& device) : device_(device) {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &engine::shaders::fullscreen_vert;
    d.depthFormat = Format::D32FS8;
    // The fragment shader's stencil replaces the reference (gl_FragStencilRefARB).
    d.stencil = {true, CompareOp::Always, 0, 0xff, 0xff, StencilOp::Replace};
    d.debugName = "cascade classify";
    const rhi::ShaderBinary* byCount[3] = {&shaders::cascade_classify_2_frag,
                                           &shaders::cascade_classify_3_frag,
                                           &shaders::cascade_classify_4_frag};
    for (size_t i = 0; i < pipelines_.size(); ++i) {
        d.fragment = byCount[i];
        pipelines_[i] = device.createPipeline(d);
    }
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

CascadeClasses::~CascadeClasses() {
    device_.waitIdle();
    if (target_) device_.destroy(target_);
    for (rhi::GraphicsPipelineHandle p : pipelines_)
        device_.destroy(p);
    device_.destroy(pointSampler_);
}

bool CascadeClasses::wanted(const rhi::Device& device) {
    return device.caps().maskedBranches && device.caps().shaderStencilExport;
}

void CascadeClasses::configureLookupDraw(rhi::GraphicsPipelineDesc& desc, uint32_t cascade, bool blend) {
    configureClassDraw(desc, kLookupField, uint8_t(kLookedUp | cascade | (blend ? 4u : 0u)));
}

void CascadeClasses::configureGlossyDraw(rhi::GraphicsPipelineDesc& desc, uint32_t cascade) {
    configureClassDraw(desc, kGlossyField, uint8_t(kMarched | cascade << 4));
}

void CascadeClasses::record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                            const engine::GBufferView& gbuffer, std::span<const VolumeGrid> cascades,
                            float blendBand, float glossyMaxRoughness, uint32_t width, uint32_t height,
                            uint32_t divisor) {
    using namespace rhi;
    // Made on the first frame and when the lookup's size changes (a resize or gi.resolution), not
    // in a steady-state frame. Only devices that run both sides of every branch need it, and a
    // console's GPU would not: its bytes are the device's ("device.cascade_classes", listed in the
    // profiler's report), not counted against the platform's GI memory budget ("gi.*").
    if (!target_ || device_.desc(target_).width != width || device_.desc(target_).height != height) {
        if (target_) {
            device_.waitIdle();
            device_.destroy(target_);
        }
        target_ = device_.createTexture({TextureKind::Tex2D, Format::D32FS8, width, height, 1, 1,
                                         kTextureDepthTarget, "cascade classes", "device.cascade_classes"});
    }
    ClassifyUniforms u;
    u.invViewProjection = camera.invViewProjection;
    for (uint32_t c = 0; c < 4; ++c) {
        const VolumeGrid& g = cascades[std::min<size_t>(c, cascades.size() - 1)];
        u.gridOrigin[c] = glm::vec4(g.origin, g.cellSize);
    }
    u.grid = glm::ivec4(int(cascades[0].size), 0, 0, 0);
    u.band = glm::vec4(blendBand, glossyMaxRoughness, 0, 0);
    u.pixels = glm::ivec4(int(divisor), int(gbuffer.width), int(gbuffer.height), 0);
    RenderPassDesc pass;
    pass.depth = {target_, 0, LoadOp::Clear, 1.0f, 0};
    pass.debugName = "cascade classify";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipelines_[cascades.size() - 2]);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindTexture(1, gbuffer.depth, pointSampler_);
    cmd.bindTexture(2, gbuffer.normal, pointSampler_);
    cmd.draw(3);
    cmd.endRenderPass();
}

void bindCascadeReads(rhi::CommandList& cmd, const engine::GBufferView& gbuffer,
                      std::span<const std::array<rhi::TextureHandle, 3>> finestFirst,
                      rhi::SamplerHandle point, rhi::SamplerHandle linear) {
    cmd.bindTexture(1, gbuffer.depth, point);
    cmd.bindTexture(2, gbuffer.normal, point);
    for (uint32_t c = 0; c < 4; ++c)
        for (uint32_t ch = 0; ch < 3; ++ch)
            cmd.bindTexture(3 + 3 * c + ch, finestFirst[std::min<size_t>(c, finestFirst.size() - 1)][ch],
                            linear);
}

} // namespace lpv::gi
