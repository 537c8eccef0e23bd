// The analytic-lights pass: packing, upload and the dispatch over the volume's cells.
#include "gi/PointLightInjection.h"

#include "GiShaders.h"
#include "rhi/Error.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::gi {
namespace {

const engine::BoolSetting kAnalyticLights{
    "gi.analytic_lights", true,
    "Point and spot lights lit through the LPV (added analytically, no RSM) instead of per pixel"};

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

// Cells inside the light's range: the sphere's volume in cells, at most the whole volume.
uint64_t cellsInRange(const AnalyticLight& light, const VolumeGrid& grid) {
    const double all = double(grid.size) * grid.size * grid.size;
    const double range = light.positionRange.w;
    if (range <= 0.0) return uint64_t(all);
    const double r = range / grid.cellSize;
    return uint64_t(std::min(all, 4.0 / 3.0 * 3.14159265358979 * r * r * r));
}

} // namespace

bool analyticLightsEnabled(const engine::Config& config) {
    return config.get(kAnalyticLights);
}

PointLightInjection::PointLightInjection(rhi::Device& device, const LpvSettings& settings)
    : device_(device), format_(shTextureFormat(settings.shFormat)) {
    using namespace rhi;
    buffer_ = device.createBuffer({kBufferBytes, kBufferStorage | kBufferTransfer, MemoryAccess::GpuOnly,
                                   "analytic lights", "gi.lights"});
    pipeline_ = device.createPipeline(
        ComputePipelineDesc{&pointLightShader(settings.shFormat), "lpv analytic lights"});
}

PointLightInjection::~PointLightInjection() {
    device_.waitIdle();
    device_.destroy(buffer_);
    device_.destroy(pipeline_);
}

uint32_t PointLightInjection::inject(rhi::CommandList& cmd, std::span<const engine::Light> lights,
                                     const LpvVolumes& volumes, const VolumeGrid& grid,
                                     float intensityScale) {
    count_ = 0;
    reachedCells_ = 0;
    for (const engine::Light& l : lights) {
        if (count_ == kMaxLights) break;
        if (l.type == engine::LightType::Directional) continue;
        const AnalyticLight a = analyticLight(l, intensityScale);
        if (!reachesVolume(a, grid)) continue;
        staged_[count_++] = a;
        reachedCells_ += cellsInRange(a, grid);
    }
    if (count_ == 0) return 0;
    if (device_.desc(volumes.accumulated()[0]).format != format_)
        throw rhi::Error("analytic lights: the volumes' format changed without remaking the pass");
    cmd.updateBuffer(buffer_, 0, staged_.data(), uint32_t(count_ * sizeof(AnalyticLight)));
    PointLightUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    u.grid = glm::ivec4(int(volumes.gridSize()), int(count_), 0, 0);
    u.encode = glm::vec4(volumes.encodeRange(), 0, 0, 0);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindStorageBuffer(1, buffer_);
    for (uint32_t c = 0; c < 3; ++c)
        cmd.bindStorageImage(2 + c, volumes.accumulated()[c]);
    const uint32_t n = volumes.gridSize();
    cmd.dispatch((n + 7) / 8, (n + 7) / 8, n);
    return count_;
}

engine::WorkCounts analyticLightsWork(const LpvSettings& s, uint32_t lightCount, uint64_t reachedCells) {
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    const uint64_t bpp = rhi::bytesPerPixel(shTextureFormat(s.shFormat));
    const uint64_t touched = std::min(cells, reachedCells); // cells some light reaches, at most
    engine::WorkCounts w;
    if (lightCount == 0) return w;
    w.cells = cells;
    // Every cell tests every light (distance and range, 8 operations); a light in range costs the
    // own-cell test, rsqrt, window, cone and three 4-coefficient MADs (about 60).
    w.aluOps = cells * lightCount * 8 + reachedCells * 60;
    // Reached cells read and write the three accumulated SH textures.
    w.texelsRead = touched * 3;
    w.texelsWritten = touched * 3;
    // Light records come from memory once (then from cache), plus the upload.
    w.bytesMoved = uint64_t(lightCount) * sizeof(AnalyticLight) * 2 + touched * 3 * bpp * 2;
    return w;
}

} // namespace lpv::gi
