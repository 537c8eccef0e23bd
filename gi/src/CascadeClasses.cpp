// The cascade classification pass and the pipeline state of a class draw.
#include "gi/CascadeClasses.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace lpv::gi {
namespace {

// std140 block `Classify` of cascade_classify.frag.
struct ClassifyUniforms {
    glm::mat4 invViewProjection;
    glm::vec4 gridOrigin[4];
    glm::ivec4 grid;
    glm::vec4 band;
    glm::ivec4 pixels;
};

} // namespace

CascadeClasses::CascadeClasses(rhi::Device& device) : device_(device) {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &shaders::cascade_classes_vert;
    d.fragment = &shaders::cascade_classify_frag;
    d.depthTest = true;
    d.depthWrite = true;
    d.depthCompare = CompareOp::Always;
    d.depthFormat = Format::D32F;
    d.debugName = "cascade classify";
    pipeline_ = device.createPipeline(d);
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

CascadeClasses::~CascadeClasses() {
    device_.waitIdle();
    if (depth_) device_.destroy(depth_);
    device_.destroy(pipeline_);
    device_.destroy(pointSampler_);
}

void CascadeClasses::configureClassDraw(rhi::GraphicsPipelineDesc& desc) {
    desc.vertex = &shaders::cascade_classes_vert;
    desc.depthTest = true;
    desc.depthWrite = false;
    desc.depthCompare = rhi::CompareOp::Equal;
    desc.depthFormat = rhi::Format::D32F;
}

void CascadeClasses::classify(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                              const engine::GBufferView& gbuffer, std::span<const VolumeGrid> cascades,
                              float blendBand, bool glossy, uint32_t width, uint32_t height,
                              uint32_t divisor) {
    using namespace rhi;
    // Made on the first frame and when the lookup's size changes (a resize or gi.resolution), not
    // in a steady-state frame. Its bytes are GI's, next to the lookup targets' render.lighting.
    if (!depth_ || device_.desc(depth_).width != width || device_.desc(depth_).height != height) {
        if (depth_) {
            device_.waitIdle();
            device_.destroy(depth_);
        }
        depth_ = device_.createTexture({TextureKind::Tex2D, Format::D32F, width, height, 1, 1,
                                        kTextureDepthTarget, "cascade classes", "gi.lookup"});
    }
    ClassifyUniforms u;
    u.invViewProjection = camera.invViewProjection;
    for (uint32_t c = 0; c < 4; ++c) {
        const VolumeGrid& g = cascades[std::min<size_t>(c, cascades.size() - 1)];
        u.gridOrigin[c] = glm::vec4(g.origin, g.cellSize);
    }
    u.grid = glm::ivec4(int(cascades[0].size), int(cascades.size()), glossy ? 1 : 0, 0);
    u.band = glm::vec4(blendBand, 0, 0, 0);
    u.pixels = glm::ivec4(int(divisor), int(gbuffer.width), int(gbuffer.height), 0);
    RenderPassDesc pass;
    pass.depth = {depth_, 0, LoadOp::Clear, 1.0f};
    pass.debugName = "cascade classify";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindTexture(1, gbuffer.depth, pointSampler_);
    cmd.bindTexture(2, gbuffer.normal, pointSampler_);
    cmd.draw(3); // class 0's triangle; the shader writes each texel's own depth
    cmd.endRenderPass();
}

void bindCascadeVolumes(rhi::CommandList& cmd, std::span<const std::array<rhi::TextureHandle, 3>> finestFirst,
                        rhi::SamplerHandle sampler) {
    for (uint32_t c = 0; c < 4; ++c)
        for (uint32_t ch = 0; ch < 3; ++ch)
            cmd.bindTexture(3 + 3 * c + ch, finestFirst[std::min<size_t>(c, finestFirst.size() - 1)][ch],
                            sampler);
}

} // namespace lpv::gi
