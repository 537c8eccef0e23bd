// The fog march: uniforms, bindings and one fullscreen triangle.
#include "gi/FogMarch.h"

#include "EngineShaders.h"
#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace lpv::gi {
namespace {

// std140 block `Fog` of fog_march.glsl.
struct FogUniforms {
    glm::mat4 invViewProjection;
    glm::mat4 sunViewProjection;
    glm::vec4 cameraPosition; // w: the sun's depth bias
    glm::vec4 sunDirection;   // w: Henyey-Greenstein g
    glm::vec4 sunRadiance;    // w: 1 with a shadow map
    glm::vec4 scattering;     // rgb: albedo, w: density
    glm::vec4 height;         // x: falloff, y: base height, z: rgba8 range
    glm::vec4 boundsMin, boundsMax;
    glm::vec4 gridOrigin[4];
    glm::ivec4 pixels; // x: divisor, y: steps, zw: G-buffer size
    glm::ivec4 grid;   // x: cells per axis, y: rgba8-encoded
};

} // namespace

FogMarch::FogMarch(rhi::Device& device) : device_(device) {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &engine::shaders::fullscreen_vert;
    d.colorFormats = {Format::RGBA16F};
    d.debugName = "fog march";
    const rhi::ShaderBinary* marches[5] = {&shaders::fog_march_0_frag, &shaders::fog_march_1_frag,
                                           &shaders::fog_march_2_frag, &shaders::fog_march_3_frag,
                                           &shaders::fog_march_4_frag};
    for (size_t c = 0; c < 5; ++c) {
        d.fragment = marches[c];
        pipelines_[c] = device.createPipeline(d);
    }
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linearSampler_ = device.createSampler(linear);
    SamplerDesc compare;
    compare.mipFilter = Filter::Nearest;
    compare.compareEnable = true;
    compare.compareOp = CompareOp::LessOrEqual;
    compare.debugName = "fog shadow compare";
    shadowSampler_ = device.createSampler(compare);
}

FogMarch::~FogMarch() {
    for (rhi::GraphicsPipelineHandle p : pipelines_)
        device_.destroy(p);
    for (rhi::SamplerHandle s : {pointSampler_, linearSampler_, shadowSampler_})
        device_.destroy(s);
}

void FogMarch::record(rhi::CommandList& cmd, const FogSettings& settings, const FogInputs& inputs,
                      rhi::TextureHandle target) {
    using namespace rhi;
    const size_t cascades = std::min<size_t>(inputs.cascades.size(), 4);
    FogUniforms u{};
    u.invViewProjection = inputs.camera.invViewProjection;
    u.sunViewProjection = inputs.sun.viewProjection;
    u.cameraPosition = glm::vec4(inputs.camera.position, inputs.sun.depthBias);
    u.sunDirection = glm::vec4(inputs.sun.direction, settings.anisotropy);
    u.sunRadiance = glm::vec4(inputs.sun.radiance, inputs.sun.shadowMap ? 1.0f : 0.0f);
    u.scattering = glm::vec4(settings.albedo, settings.density);
    u.height = glm::vec4(settings.heightFalloff, settings.baseHeight, inputs.rgba8Range, 0.0f);
    // An empty scene: rays that meet nothing stop at the camera.
    const engine::Bounds& b = inputs.sceneBounds;
    u.boundsMin = glm::vec4(b.empty() ? inputs.camera.position : b.min, 0.0f);
    u.boundsMax = glm::vec4(b.empty() ? inputs.camera.position : b.max, 0.0f);
    for (size_t c = 0; c < cascades; ++c)
        u.gridOrigin[c] = glm::vec4(inputs.cascades[c].grid.origin, inputs.cascades[c].grid.cellSize);
    u.pixels = glm::ivec4(int(settings.resolutionDivisor), int(settings.steps), int(inputs.gbuffer.width),
                          int(inputs.gbuffer.height));
    u.grid = glm::ivec4(cascades > 0 ? int(inputs.cascades[0].grid.size) : 1,
                        inputs.rgba8Range > 0.0f ? 1 : 0, int(cascades), 0);
    RenderPassDesc pass;
    pass.colors[0] = {target, 0, 0, LoadOp::DontCare};
    pass.colorCount = 1;
    pass.debugName = "fog march";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipelines_[cascades]);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindTexture(1, inputs.gbuffer.depth, pointSampler_);
    // Without a shadow map the binding is unread (sunRadiance.w = 0); the depth fills it.
    cmd.bindTexture(2, inputs.sun.shadowMap ? inputs.sun.shadowMap : inputs.gbuffer.depth, shadowSampler_);
    // lpv_cascades.glsl declares four cascades' volumes: those past the count repeat the coarsest.
    if (cascades > 0)
        for (size_t c = 0; c < 4; ++c)
            for (uint32_t ch = 0; ch < 3; ++ch)
                cmd.bindTexture(uint32_t(3 + 3 * c + ch), inputs.cascades[std::min(c, cascades - 1)].sh[ch],
                                linearSampler_);
    cmd.draw(3);
    cmd.endRenderPass();
}

engine::WorkCounts fogWork(const FogSettings& settings, uint64_t texels, bool indirect) {
    engine::WorkCounts w;
    const uint64_t steps = settings.steps;
    w.pixelsShaded = texels;
    // A 3D (trilinear) fetch costs two bilinear ones on the cost model's texture units.
    w.texelsRead = texels * (1 + steps * (1 + (indirect ? 3 * 2 : 0)));
    w.texelsWritten = texels;
    // The ray and its end (60), then per step the density, the phase, the shadow projection and
    // the segment's integral (50), and the SH products (25).
    w.aluOps = texels * (60 + steps * (50 + (indirect ? 25 : 0)));
    w.bytesMoved = texels * (4 + 8);
    w.primitives = 1;
    return w;
}

} // namespace lpv::gi
