// Injection and propagation passes.
#include "gi/LpvVolumes.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

namespace lpv::gi {
namespace {

struct InjectUniforms {
    glm::vec4 gridOrigin;
    glm::vec4 lightDirection;
    glm::vec4 intensity;
    glm::ivec4 grid;
};

struct PropagateUniforms {
    glm::ivec4 grid;
    glm::vec4 encode;
};

const rhi::ShaderBinary& propagateShader(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return shaders::propagate_rgba8_comp;
    case ShFormat::Rgba32f:
        return shaders::propagate_rgba32f_comp;
    case ShFormat::Rgba16f:
        break;
    }
    return shaders::propagate_rgba16f_comp;
}

} // namespace

LpvVolumes::LpvVolumes(rhi::Device& device, const LpvSettings& settings)
    : device_(device), settings_(settings) {
    using namespace rhi;
    const uint32_t n = settings.gridSize;
    const Format injectFormat = settings.shFormat == ShFormat::Rgba32f ? Format::RGBA32F : Format::RGBA16F;
    const Format shFormat = shTextureFormat(settings.shFormat);
    const char* channels[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c) {
        const auto volume = [&](Format f, uint32_t usage, const char* what) {
            return device.createTexture({TextureKind::Tex3D, f, n, n, n, 1, usage | kTextureTransfer,
                                         std::string("lpv ") + what + " " + channels[c], "gi.lpv"});
        };
        inject_[size_t(c)] = volume(injectFormat, kTextureColorTarget | kTextureSampled, "injection");
        ping_[size_t(c)] = volume(shFormat, kTextureStorage | kTextureSampled, "ping");
        pong_[size_t(c)] = volume(shFormat, kTextureStorage | kTextureSampled, "pong");
        accum_[size_t(c)] = volume(shFormat, kTextureStorage | kTextureSampled, "accumulated");
    }
    GraphicsPipelineDesc d;
    d.vertex = &shaders::inject_vert;
    d.fragment = &shaders::inject_frag;
    d.topology = PrimitiveTopology::PointList;
    d.colorFormats = {injectFormat, injectFormat, injectFormat};
    d.blend = {BlendState::additive()};
    d.debugName = "lpv inject";
    injectPipeline_ = device.createPipeline(d);
    propagatePipeline_ =
        device.createPipeline(ComputePipelineDesc{&propagateShader(settings.shFormat), "lpv propagate"});
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

LpvVolumes::~LpvVolumes() {
    device_.waitIdle();
    for (const auto* set : {&inject_, &ping_, &pong_, &accum_})
        for (rhi::TextureHandle t : *set)
            device_.destroy(t);
    device_.destroy(injectPipeline_);
    device_.destroy(propagatePipeline_);
    device_.destroy(pointSampler_);
}

bool LpvVolumes::matches(const LpvSettings& s) const {
    return s.gridSize == settings_.gridSize && s.shFormat == settings_.shFormat &&
           s.rgba8Range == settings_.rgba8Range;
}

void LpvVolumes::inject(rhi::CommandList& cmd, rhi::BufferHandle vpls, uint32_t vplCount,
                        const VolumeGrid& grid, glm::vec3 lightDirection, float intensity) {
    using namespace rhi;
    for (TextureHandle t : inject_)
        cmd.clearTexture(t, {0, 0, 0, 0});
    InjectUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    u.lightDirection = glm::vec4(lightDirection, 0.0f);
    u.intensity = glm::vec4(intensity, 0, 0, 0);
    for (uint32_t slice = 0; slice < settings_.gridSize; ++slice) {
        RenderPassDesc pass;
        for (uint32_t c = 0; c < 3; ++c)
            pass.colors[c] = {inject_[c], 0, slice, LoadOp::Load};
        pass.colorCount = 3;
        pass.debugName = "lpv inject slice";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(injectPipeline_);
        u.grid = glm::ivec4(int(settings_.gridSize), int(slice), int(vplCount), 0);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindStorageBuffer(1, vpls);
        cmd.draw(vplCount);
        cmd.endRenderPass();
    }
}

void LpvVolumes::propagate(rhi::CommandList& cmd, uint32_t iterations) {
    const uint32_t n = settings_.gridSize;
    const std::array<rhi::TextureHandle, 3>* src = &inject_;
    for (uint32_t i = 0; i < iterations; ++i) {
        const std::array<rhi::TextureHandle, 3>* dst = (i % 2 == 0) ? &ping_ : &pong_;
        PropagateUniforms u;
        u.grid = glm::ivec4(int(n), i == 0 ? 1 : 0, (i > 0 && encoded()) ? 1 : 0, 0);
        u.encode = glm::vec4(settings_.rgba8Range, 0, 0, 0);
        cmd.bindPipeline(propagatePipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        for (uint32_t c = 0; c < 3; ++c) {
            cmd.bindTexture(1 + c, (*src)[c], pointSampler_);
            cmd.bindStorageImage(4 + c, (*dst)[c]);
            cmd.bindStorageImage(7 + c, accum_[c]);
        }
        cmd.dispatch((n + 7) / 8, (n + 7) / 8, n);
        src = dst;
    }
}

} // namespace lpv::gi
