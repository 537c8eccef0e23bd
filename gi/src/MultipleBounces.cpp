// Multiple bounces: reflect, propagate, add, per further bounce.
#include "gi/MultipleBounces.h"

#include "GiShaders.h"
#include "gi/GeometryVolume.h"

#include <glm/vec4.hpp>

namespace lpv::gi {
namespace {

struct BounceUniforms {
    glm::ivec4 grid;
    glm::vec4 encode;
};

const rhi::ShaderBinary& reflectShader(ShFormat f) {
    // The injection volume blends in half floats unless the volumes are rgba32f (LpvVolumes).
    return f == ShFormat::Rgba32f ? shaders::lpv_reflect_rgba32f_comp : shaders::lpv_reflect_rgba16f_comp;
}

const rhi::ShaderBinary& addShader(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return shaders::lpv_bounce_add_rgba8_comp;
    case ShFormat::Rgba32f:
        return shaders::lpv_bounce_add_rgba32f_comp;
    case ShFormat::Rgba16f:
        break;
    }
    return shaders::lpv_bounce_add_rgba16f_comp;
}

} // namespace

MultipleBounces::MultipleBounces(rhi::Device& device, const LpvSettings& settings, const LpvVolumes& volumes)
    : device_(device), settings_(settings) {
    using namespace rhi;
    bounce_ = volumes.createResult("lpv bounce");
    reflectPipeline_ =
        device.createPipeline(ComputePipelineDesc{&reflectShader(settings.shFormat), "lpv bounce reflect"});
    addPipeline_ =
        device.createPipeline(ComputePipelineDesc{&addShader(settings.shFormat), "lpv bounce add"});
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

MultipleBounces::~MultipleBounces() {
    device_.waitIdle();
    for (rhi::TextureHandle t : bounce_)
        device_.destroy(t);
    device_.destroy(reflectPipeline_);
    device_.destroy(addPipeline_);
    device_.destroy(pointSampler_);
}

void MultipleBounces::record(rhi::CommandList& cmd, LpvVolumes& volumes, LpvPropagation& propagation,
                             const GeometryVolume& geometry, uint32_t bounces, uint32_t iterations,
                             const std::array<rhi::TextureHandle, 3>& result) {
    const uint32_t n = settings_.gridSize;
    const uint32_t groups = (n + 3) / 4;
    BounceUniforms u;
    u.grid = glm::ivec4(int(n), 0, 0, 0);
    // The cascade's own range: its light was injected last (LightPropagationVolume::renderIndirect).
    u.encode = glm::vec4(volumes.injectedEncodeRange(), volumes.encoded() ? 1.0f : 0.0f, 0, 0);
    // The first further bounce reflects the cascade's light; each later one the previous bounce's.
    const std::array<rhi::TextureHandle, 3>* source = &result;
    for (uint32_t b = 1; b < bounces; ++b) {
        cmd.bindPipeline(reflectPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        for (uint32_t c = 0; c < 3; ++c) {
            cmd.bindTexture(4 + c, (*source)[c], pointSampler_);
            cmd.bindStorageImage(1 + c, volumes.injected()[c]);
        }
        cmd.bindTexture(7, geometry.faceTransmittance(), pointSampler_);
        cmd.bindTexture(8, geometry.surfelAlbedo(), pointSampler_);
        cmd.dispatch(groups, groups, groups);

        propagation.record(cmd, volumes, iterations, geometry.faceTransmittance(), &bounce_);

        cmd.bindPipeline(addPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        for (uint32_t c = 0; c < 3; ++c) {
            cmd.bindTexture(1 + c, bounce_[c], pointSampler_);
            cmd.bindStorageImage(4 + c, result[c]);
        }
        if (Rgba8Clipping* clipping = volumes.clipping()) clipping->bind(cmd, volumes.injectedCascade());
        cmd.dispatch(groups, groups, groups);
        source = &bounce_;
    }
}

} // namespace lpv::gi
