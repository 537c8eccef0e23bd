// Multiple bounces: reflect, propagate, add, per further bounce.
#include "gi/MultipleBounces.h"

#include "GiShaders.h"
#include "gi/GeometryVolume.h"

#include <glm/vec4.hpp>

#include <stdexcept>

namespace lpv::gi {
namespace {

struct BounceUniforms {
    glm::ivec4 grid;
    glm::vec4 encode;
    glm::ivec4 shift; // the reflection's (lpv_reflect_body.glsl)
};

const rhi::ShaderBinary& reflectShader(ShFormat f) {
    // The injection volume blends in half floats unless the volumes are rgba32f (LpvVolumes).
    return f == ShFormat::Rgba32f ? shaders::lpv_reflect_rgba32f_comp : shaders::lpv_reflect_rgba16f_comp;
}

const rhi::ShaderBinary& addShader(ShFormat f, bool keep) {
    switch (f) {
    case ShFormat::Rgba8:
        return keep ? shaders::lpv_bounce_add_rgba8_keep_comp : shaders::lpv_bounce_add_rgba8_comp;
    case ShFormat::Rgba32f:
        return keep ? shaders::lpv_bounce_add_rgba32f_keep_comp : shaders::lpv_bounce_add_rgba32f_comp;
    case ShFormat::Rgba16f:
        break;
    }
    return keep ? shaders::lpv_bounce_add_rgba16f_keep_comp : shaders::lpv_bounce_add_rgba16f_comp;
}

} // namespace

MultipleBounces::MultipleBounces(rhi::Device& device, const LpvSettings& settings, const LpvVolumes& volumes,
                                 bool keepFirst, bool partialSums)
    : device_(device), settings_(settings) {
    using namespace rhi;
    if (keepFirst) {
        if (settings.shFormat == ShFormat::Rgba8)
            throw std::logic_error("MultipleBounces: the first bounce is kept apart in float volumes only");
        own_ = std::make_unique<LpvVolumes>(device, settings, partialSums);
        bounce_ = own_->accumulated();
        first_ = volumes.createResult("lpv first bounce");
        addFirstPipeline_ = device.createPipeline(ComputePipelineDesc{
            settings.shFormat == ShFormat::Rgba32f ? &shaders::lpv_bounce_add_rgba32f_first_comp
                                                   : &shaders::lpv_bounce_add_rgba16f_first_comp,
            "lpv bounce add (first apart)"});
        addFirstKeepPipeline_ = device.createPipeline(ComputePipelineDesc{
            settings.shFormat == ShFormat::Rgba32f ? &shaders::lpv_bounce_add_rgba32f_first_keep_comp
                                                   : &shaders::lpv_bounce_add_rgba16f_first_keep_comp,
            "lpv bounce add (first apart, kept)"});
    } else {
        bounce_ = volumes.createResult("lpv bounce");
    }
    reflectPipeline_ =
        device.createPipeline(ComputePipelineDesc{&reflectShader(settings.shFormat), "lpv bounce reflect"});
    addPipeline_ =
        device.createPipeline(ComputePipelineDesc{&addShader(settings.shFormat, false), "lpv bounce add"});
    // gi.gather: the sum of the first two bounces kept for the lookup (GatheredReflection).
    addKeepPipeline_ = device.createPipeline(
        ComputePipelineDesc{&addShader(settings.shFormat, true), "lpv bounce add (kept)"});
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

MultipleBounces::~MultipleBounces() {
    device_.waitIdle();
    if (!own_)
        for (rhi::TextureHandle t : bounce_)
            device_.destroy(t);
    for (rhi::TextureHandle t : first_)
        if (t) device_.destroy(t);
    device_.destroy(reflectPipeline_);
    device_.destroy(addPipeline_);
    if (addFirstPipeline_) device_.destroy(addFirstPipeline_);
    device_.destroy(addKeepPipeline_);
    if (addFirstKeepPipeline_) device_.destroy(addFirstKeepPipeline_);
    device_.destroy(pointSampler_);
}

void MultipleBounces::recordReflect(rhi::CommandList& cmd, LpvVolumes& into, const GeometryVolume& geometry,
                                    const std::array<rhi::TextureHandle, 3>& source, glm::ivec3 shift) {
    const uint32_t n = settings_.gridSize;
    const uint32_t groups = (n + 3) / 4;
    BounceUniforms u;
    u.grid = glm::ivec4(int(n), 0, 0, 0);
    // The cascade's own range: its light was injected last (LightPropagationVolume::renderIndirect).
    u.encode = glm::vec4(into.injectedEncodeRange(), into.encoded() ? 1.0f : 0.0f, 0, 0);
    u.shift = glm::ivec4(shift, 0);
    cmd.bindPipeline(reflectPipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    for (uint32_t c = 0; c < 3; ++c) {
        cmd.bindTexture(4 + c, source[c], pointSampler_);
        cmd.bindStorageImage(1 + c, into.injected()[c]);
    }
    cmd.bindTexture(7, geometry.faceTransmittance(), pointSampler_);
    cmd.bindTexture(8, geometry.surfelAlbedo(), pointSampler_);
    cmd.dispatch(groups, groups, groups);
}

PropagationJob MultipleBounces::job(LpvVolumes& volumes, const GeometryVolume& geometry) {
    return {&volumes, geometry.faceTransmittance(), &bounce_, nullptr};
}

void MultipleBounces::recordAdd(rhi::CommandList& cmd, LpvVolumes& volumes,
                                const std::array<rhi::TextureHandle, 3>& result,
                                const std::array<rhi::TextureHandle, 3>* first,
                                const std::array<rhi::TextureHandle, 3>* keep) {
    const uint32_t n = settings_.gridSize;
    const uint32_t groups = (n + 3) / 4;
    BounceUniforms u;
    u.grid = glm::ivec4(int(n), 0, 0, 0);
    u.encode = glm::vec4(volumes.injectedEncodeRange(), volumes.encoded() ? 1.0f : 0.0f, 0, 0);
    u.shift = glm::ivec4(0);
    if (first && !addFirstPipeline_)
        throw std::logic_error("MultipleBounces::recordAdd: made without keepFirst");
    cmd.bindPipeline(first ? (keep ? addFirstKeepPipeline_ : addFirstPipeline_)
                           : (keep ? addKeepPipeline_ : addPipeline_));
    cmd.pushUniforms(0, &u, sizeof(u));
    for (uint32_t c = 0; c < 3; ++c) {
        cmd.bindTexture((keep ? 10 : 1) + c, bounce_[c], pointSampler_);
        cmd.bindStorageImage(4 + c, result[c]);
        if (first) cmd.bindTexture(7 + c, (*first)[c], pointSampler_);
        if (keep) cmd.bindStorageImage(1 + c, (*keep)[c]);
    }
    if (Rgba8Clipping* clipping = volumes.clipping()) clipping->bind(cmd, volumes.injectedCascade());
    cmd.dispatch(groups, groups, groups);
}

void MultipleBounces::record(rhi::CommandList& cmd, LpvVolumes& volumes, LpvPropagation& propagation,
                             const GeometryVolume& geometry, uint32_t bounces, uint32_t iterations,
                             const std::array<rhi::TextureHandle, 3>& result,
                             const std::array<rhi::TextureHandle, 3>* first, bool reflected,
                             const std::array<rhi::TextureHandle, 3>* keepSecond) {
    // The first further bounce reflects the cascade's light; each later one the previous bounce's.
    const std::array<rhi::TextureHandle, 3>* source = first ? first : &result;
    for (uint32_t b = 1; b < bounces; ++b) {
        if (b > 1 || !reflected) recordReflect(cmd, volumes, geometry, *source);
        propagation.record(cmd, volumes, iterations, geometry.faceTransmittance(), &bounce_);
        recordAdd(cmd, volumes, result, b == 1 ? first : nullptr, b == 1 ? keepSecond : nullptr);
        source = &bounce_;
    }
}

void MultipleBounces::recordFurther(rhi::CommandList& cmd, LpvVolumes& volumes, LpvPropagation& propagation,
                                    const GeometryVolume& geometry, uint32_t iterations,
                                    const std::array<rhi::TextureHandle, 3>& result,
                                    const std::array<rhi::TextureHandle, 3>* keep) {
    propagation.record(cmd, volumes, iterations, geometry.faceTransmittance(), &bounce_);
    recordAdd(cmd, volumes, result, nullptr, keep);
}

} // namespace lpv::gi
