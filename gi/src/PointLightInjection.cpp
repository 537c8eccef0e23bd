// The analytic-lights pass: packing, upload and the dispatch over the volume's cells.
#include "gi/PointLightInjection.h"

#include <string>

#include "GiShaders.h"
#include "rhi/Error.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::gi {
namespace {

constexpr uint32_t kBlock = 4; // cells per side of a shader group (point_lights_body.glsl)

struct PointLightUniforms {
    glm::vec4 gridOrigin;
    glm::ivec4 grid;
    glm::vec4 encode;
};

const rhi::ShaderBinary& pointLightShader(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return shaders::point_lights_rgba8_comp;
    case ShFormat::Rgba32f:
        return shaders::point_lights_rgba32f_comp;
    case ShFormat::Rgba16f:
        break;
    }
    return shaders::point_lights_rgba16f_comp;
}

// The cells of the shader's 4x4x4 blocks that the light's range box overlaps: the cells that
// evaluate the light (all of them for an infinite range).
uint64_t cellsEvaluating(const AnalyticLight& light, const VolumeGrid& grid) {
    const uint32_t blocks = (grid.size + kBlock - 1) / kBlock;
    if (light.positionInvRange2.w <= 0.0f)
        return uint64_t(blocks) * blocks * blocks * kBlock * kBlock * kBlock;
    const glm::vec3 p(light.positionInvRange2);
    const float range = 1.0f / std::sqrt(light.positionInvRange2.w);
    const float blockSize = grid.cellSize * float(kBlock);
    const glm::ivec3 lo =
        glm::clamp(glm::ivec3(glm::floor((p - range - grid.origin) / blockSize)), 0, int(blocks) - 1);
    const glm::ivec3 hi =
        glm::clamp(glm::ivec3(glm::floor((p + range - grid.origin) / blockSize)), 0, int(blocks) - 1);
    const glm::ivec3 span = hi - lo + 1;
    return uint64_t(span.x) * uint64_t(span.y) * uint64_t(span.z) * kBlock * kBlock * kBlock;
}

} // namespace

PointLightInjection::PointLightInjection(rhi::Device& device, const LpvSettings& settings)
    : device_(device), format_(shTextureFormat(settings.shFormat)) {
    using namespace rhi;
    // One buffer per cascade: each cascade's lights are uploaded before any of them is read, so
    // no upload waits for the previous cascade's dispatch.
    for (uint32_t c = 0; c < settings.cascades; ++c)
        buffers_[c] =
            device.createBuffer({kBufferBytes, kBufferUniform | kBufferTransfer, MemoryAccess::GpuOnly,
                                 "analytic lights, cascade " + std::to_string(c), "gi.lights"});
    pipeline_ = device.createPipeline(
        ComputePipelineDesc{&pointLightShader(settings.shFormat), "lpv analytic lights"});
}

PointLightInjection::~PointLightInjection() {
    device_.waitIdle();
    for (rhi::BufferHandle b : buffers_)
        if (b) device_.destroy(b);
    device_.destroy(pipeline_);
}

uint32_t PointLightInjection::record(rhi::CommandList& cmd, std::span<const engine::Light> lights,
                                     LpvVolumes& volumes, const VolumeGrid& grid, float intensityScale,
                                     const std::array<rhi::TextureHandle, 3>* result, uint32_t cascade,
                                     std::span<const uint32_t> skip) {
    const std::array<rhi::TextureHandle, 3>& target = result ? *result : volumes.accumulated();
    count_ = 0;
    cellEvaluations_ = 0;
    for (uint32_t i = 0; i < uint32_t(lights.size()); ++i) {
        const engine::Light& l = lights[i];
        if (count_ == kMaxLights) break;
        if (l.type == engine::LightType::Directional) continue;
        if (std::find(skip.begin(), skip.end(), i) != skip.end()) continue;
        const AnalyticLight a = analyticLight(l, intensityScale);
        if (!reachesVolume(a, grid)) continue;
        staged_[count_++] = a;
        cellEvaluations_ += cellsEvaluating(a, grid);
    }
    if (count_ == 0) return 0;
    if (device_.desc(target[0]).format != format_)
        throw rhi::Error("analytic lights: the volumes' format changed without remaking the pass");
    const rhi::BufferHandle buffer = buffers_.at(cascade);
    cmd.updateBuffer(buffer, 0, staged_.data(), uint32_t(count_ * sizeof(AnalyticLight)));
    PointLightUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    // z: 0, the offset the shader reads the count at (point_lights_body.glsl).
    u.grid = glm::ivec4(int(volumes.gridSize()), int(count_), 0, 0);
    u.encode = glm::vec4(volumes.encodeRange(grid), 0, 0, 0);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindUniformBuffer(1, buffer);
    for (uint32_t c = 0; c < 3; ++c)
        cmd.bindStorageImage(2 + c, target[c]);
    if (Rgba8Clipping* clipping = volumes.clipping()) clipping->bind(cmd, cascade);
    const uint32_t blocks = (volumes.gridSize() + kBlock - 1) / kBlock;
    cmd.dispatch(blocks, blocks, blocks);
    return count_;
}

engine::WorkCounts analyticLightsWork(const LpvSettings& s, uint32_t lightCount, uint64_t cellEvaluations) {
    engine::WorkCounts w;
    if (lightCount == 0) return w;
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    const uint64_t blocks = uint64_t((s.gridSize + kBlock - 1) / kBlock);
    const uint64_t bpp = rhi::bytesPerPixel(shTextureFormat(s.shFormat));
    const uint64_t touched = std::min(cells, cellEvaluations); // cells that read-modify-write, at most
    w.cells = cells;
    // Each group tests every light against its block (12 operations); each evaluation costs the
    // own-cell and range tests, rsqrt, window, cone and three 4-coefficient MADs (about 50).
    w.aluOps = blocks * blocks * blocks * lightCount * 12 + cellEvaluations * 50;
    w.texelsRead = touched * 3;
    w.texelsWritten = touched * 3;
    // The light records are uploaded and read once per group (from cache after the first), plus
    // the three SH textures' read-modify-write.
    w.bytesMoved = uint64_t(lightCount) * sizeof(AnalyticLight) * 2 + touched * 3 * bpp * 2;
    return w;
}

} // namespace lpv::gi
