// The glossy-reflection pass: uniforms, bindings and one fullscreen triangle.
#include "gi/GlossyReflections.h"

#include "EngineShaders.h"
#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace lpv::gi {
namespace {

// std140 block `Glossy` of lpv_glossy.glsl.
struct GlossyUniforms {
    glm::mat4 invViewProjection;
    glm::vec4 cameraPosition;
    glm::vec4 gridOrigin[4];
    glm::ivec4 grid;
    glm::vec4 encode;
    glm::ivec4 pixels; // x: resolution divisor, yz: G-buffer size
};

} // namespace

GlossyReflections::GlossyReflections(rhi::Device& device) : device_(device) {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &engine::shaders::fullscreen_vert;
    d.colorFormats = {Format::RGBA16F};
    // Premultiplied over the lookup's lobe-mean reflection: the march answers for its fade's share
    // (it writes radiance x fade, fade), the lookup's value keeps the rest. The target's alpha
    // (the lookup's packed normal) stays.
    d.blend = {BlendState{true, BlendFactor::One, BlendFactor::OneMinusSrcAlpha, BlendOp::Add,
                          BlendFactor::Zero, BlendFactor::One, BlendOp::Add}};
    d.debugName = "lpv glossy";
    const rhi::ShaderBinary* marches[4] = {&shaders::lpv_glossy_1_frag, &shaders::lpv_glossy_2_frag,
                                           &shaders::lpv_glossy_3_frag, &shaders::lpv_glossy_4_frag};
    for (size_t c = 0; c < 4; ++c) {
        d.fragment = marches[c];
        pipelines_[c] = device.createPipeline(d);
    }
    if (CascadeClasses::wanted(device)) {
        d.debugName = "lpv glossy, one cascade";
        const rhi::ShaderBinary* perCascade[4] = {
            &shaders::lpv_glossy_class0_frag, &shaders::lpv_glossy_class1_frag,
            &shaders::lpv_glossy_class2_frag, &shaders::lpv_glossy_class3_frag};
        for (uint32_t c = 0; c < 4; ++c) {
            d.fragment = perCascade[c];
            CascadeClasses::configureGlossyDraw(d, c);
            classPipelines_[c] = device.createPipeline(d);
        }
    }
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linearSampler_ = device.createSampler(linear);
}

GlossyReflections::~GlossyReflections() {
    for (rhi::GraphicsPipelineHandle p : pipelines_)
        device_.destroy(p);
    for (rhi::GraphicsPipelineHandle p : classPipelines_)
        if (p) device_.destroy(p);
    device_.destroy(pointSampler_);
    device_.destroy(linearSampler_);
}

void GlossyReflections::record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                               const engine::GBufferView& gbuffer, std::span<const GlossyCascade> cascades,
                               float rgba8Range, float maxRoughness, rhi::TextureHandle target,
                               rhi::TextureHandle specularAlbedoTable, uint32_t divisor,
                               const CascadeClasses* classes) {
    using namespace rhi;
    const auto cascade = [&](size_t c) -> const GlossyCascade& {
        return cascades[std::min(c, cascades.size() - 1)];
    };
    GlossyUniforms u;
    u.invViewProjection = camera.invViewProjection;
    u.cameraPosition = glm::vec4(camera.position, 1.0f);
    for (uint32_t c = 0; c < 4; ++c)
        u.gridOrigin[c] = glm::vec4(cascade(c).grid.origin, cascade(c).grid.cellSize);
    u.grid = glm::ivec4(int(cascades[0].grid.size), rgba8Range > 0.0f ? 1 : 0, int(cascades.size()), 0);
    u.encode = glm::vec4(rgba8Range, maxRoughness, 0, 0);
    // w = 0: the first column of the camera matrix, read at an index lavapipe cannot fold (shader).
    u.pixels = glm::ivec4(int(divisor), int(gbuffer.width), int(gbuffer.height), 0);
    RenderPassDesc pass;
    // Over the lookup's answer: texels of no glossy class (sky, too rough) keep it.
    pass.colors[0] = {target, 0, 0, LoadOp::Load};
    pass.colorCount = 1;
    if (classes) pass.depth = {classes->target(), 0, LoadOp::Load};
    pass.debugName = "lpv glossy";
    cmd.beginRenderPass(pass);
    std::array<std::array<rhi::TextureHandle, 3>, 4> volumes;
    for (size_t c = 0; c < cascades.size(); ++c)
        volumes[c] = cascades[c].sh;
    const auto bindInputs = [&] {
        cmd.pushUniforms(0, &u, sizeof(u));
        bindCascadeReads(cmd, gbuffer, std::span(volumes.data(), cascades.size()), pointSampler_,
                         linearSampler_);
        cmd.bindTexture(15, gbuffer.albedo, pointSampler_);
        cmd.bindTexture(16, specularAlbedoTable, linearSampler_);
    };
    if (!classes) {
        cmd.bindPipeline(pipelines_[std::min<size_t>(cascades.size(), 4) - 1]);
        bindInputs();
        cmd.draw(3);
    } else {
        // Cascade c marches the texels whose lookup is in c and those whose lookup is in c + 1
        // but whose march start c holds (the classification's glossy field).
        for (size_t c = 0; c < cascades.size(); ++c) {
            cmd.bindPipeline(classPipelines_[c]);
            bindInputs();
            cmd.draw(3);
        }
    }
    cmd.endRenderPass();
}

engine::WorkCounts glossyWork(uint64_t pixels) {
    engine::WorkCounts w;
    w.pixelsShaded = pixels;
    // A 3D (trilinear) fetch costs two bilinear ones on the cost model's texture units.
    // Depth, normal, albedo and the lobe table's two blocks (bilinear), then the steps.
    w.texelsRead = pixels * (5 + GlossyReflections::kSteps * 3 * 2);
    w.texelsWritten = pixels;
    // The lobes (glossy_lobes.glsl: three channels' and the luminance's mean direction), then per
    // step one product per channel, each with its channel's lobe (as many as with one lobe).
    w.aluOps = pixels * (40 + 30 + 20 * GlossyReflections::kSteps);
    // Depth, normal and albedo in, the blend's read and write of the RGBA16F target.
    w.bytesMoved = pixels * (4 + 8 + 4 + 8 + 8);
    w.primitives = 1;
    return w;
}

} // namespace lpv::gi
