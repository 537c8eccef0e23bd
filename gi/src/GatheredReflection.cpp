// The second bounce's reflection from gathered light: one dispatch per set of VPLs.
#include "gi/GatheredReflection.h"

#include "GiShaders.h"
#include "gi/GeometryVolume.h"
#include "gi/LpvVolumes.h"

#include <glm/gtc/constants.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <stdexcept>

namespace lpv::gi {
namespace {

// std140 block `ReflectGathered` of lpv_reflect_gathered_body.glsl.
struct ReflectGatheredUniforms {
    glm::vec4 gridOrigin;
    glm::ivec4 grid;
    glm::vec4 params;
    glm::ivec4 vpls;
};

// What one of the faces' area samples counts for, of a face's area; 0: no areas.
float areaWeight(const ReflectingFaces& faces) {
    return faces.areas && faces.areaSamples > 0 ? 1.0f / float(faces.areaSamples) : 0.0f;
}

} // namespace

GatheredReflection::GatheredReflection(rhi::Device& device, ShFormat format, uint32_t gridSize, bool fromList)
    : device_(device), room_(roomFor(gridSize)), fromList_(fromList) {
    list_ = device.createBuffer({listBytes(gridSize), rhi::kBufferStorage | rhi::kBufferTransfer,
                                 rhi::MemoryAccess::GpuOnly,
                                 fromList ? "third bounce vpls" : "second bounce vpls", "gi.vpl"});
    // Both sets of counters start at 0; each record() then clears the set the next one uses.
    const std::array<uint32_t, 2 * kPhases> zeros{};
    device.uploadBuffer(list_, 0, zeros.data(), sizeof(zeros));
    faceSlots_ =
        device.createTexture({rhi::TextureKind::Tex3D, rhi::Format::R32UI, gridSize, gridSize, gridSize, 1,
                              rhi::kTextureStorage | rhi::kTextureSampled,
                              fromList ? "third bounce face slots" : "second bounce face slots", "gi.lpv"});
    noAreas_ =
        device.createTexture({rhi::TextureKind::Tex3D, rhi::Format::R32UI, 1, 1, 1, 1,
                              rhi::kTextureSampled | rhi::kTextureTransfer, "no surface areas", "gi.lpv"});
    const uint32_t zero = 0;
    device.uploadTexture(noAreas_, 0, &zero, sizeof(zero));
    // The injection volume blends in half floats unless the volumes are rgba32f (LpvVolumes).
    const bool f32 = format == ShFormat::Rgba32f;
    pipeline_ = device.createPipeline(rhi::ComputePipelineDesc{
        fromList ? (f32 ? &shaders::lpv_reflect_gathered_rgba32f_listed_comp
                        : &shaders::lpv_reflect_gathered_rgba16f_listed_comp)
                 : (f32 ? &shaders::lpv_reflect_gathered_rgba32f_comp
                        : &shaders::lpv_reflect_gathered_rgba16f_comp),
        fromList ? "lpv bounce reflect (from the listed bounce)" : "lpv bounce reflect (gathered)"});
    pointSampler_ = device.createSampler({rhi::Filter::Nearest, rhi::Filter::Nearest, rhi::Filter::Nearest});
}

GatheredReflection::~GatheredReflection() {
    device_.destroy(list_);
    device_.destroy(faceSlots_);
    device_.destroy(noAreas_);
    device_.destroy(pipeline_);
    device_.destroy(pointSampler_);
}

void GatheredReflection::bindFrame(rhi::CommandList& cmd, LpvVolumes& into, const GeometryVolume& geometry,
                                   const ReflectingFaces& faces) {
    // This frame counts in set parity_ and clears the other one for the next: no transfer (and no
    // barrier) to reset them.
    parity_ = recorded_ ? 1u - parity_ : 0u;
    recorded_ = true;
    cmd.bindPipeline(pipeline_);
    cmd.bindStorageBuffer(5, list_);
    cmd.bindStorageImage(6, faceSlots_);
    for (uint32_t c = 0; c < 3; ++c)
        cmd.bindStorageImage(1 + c, into.injected()[c]);
    cmd.bindTexture(7, faces.transmittance, pointSampler_);
    cmd.bindTexture(8, geometry.surfelAlbedo(), pointSampler_);
    cmd.bindTexture(10, faces.areas ? faces.areas : noAreas_, pointSampler_);
}

engine::WorkCounts GatheredReflection::record(rhi::CommandList& cmd, LpvVolumes& into,
                                              const GeometryVolume& geometry, const ReflectingFaces& faces,
                                              const VolumeGrid& grid, uint32_t cascade, float intensity,
                                              std::span<const GatherSource> sources) {
    if (sources.empty()) throw std::logic_error("GatheredReflection::record: no VPLs");
    if (fromList_) throw std::logic_error("GatheredReflection::record: made fromList");
    const uint32_t n = grid.size;
    const uint32_t groups = (n + 3) / 4;
    ReflectGatheredUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    bindFrame(cmd, into, geometry, faces);
    const bool marched = faces.marched;
    const float perSample = areaWeight(faces);
    engine::WorkCounts work;
    bool first = true;
    const uint64_t cells = uint64_t(n) * n * n;
    for (const GatherSource& s : sources) {
        const bool lights =
            s.cascade == int32_t(cascade) || (s.cascade < 0 && (s.cascades & (1u << cascade)));
        if (!s.vpls || !lights) continue;
        u.grid = glm::ivec4(int(n), first ? 0 : 1, marched ? 1 : 0, 0);
        u.params = glm::vec4(intensity, s.nearest, perSample, float(faces.areaStamp));
        u.vpls = glm::ivec4(int(s.slots), int(s.side), int(room_), int(parity_));
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindStorageBuffer(4, s.vpls);
        cmd.dispatch(groups, groups, groups);
        first = false;
        // An estimate: an eighth of the cells hold a surface; each reads a quarter of the slots
        // (48 bytes, mostly from cache) for up to three lit faces, marched through about a quarter
        // of the grid's faces; every cell reads its faces and writes its injection, and one with a
        // surface the areas of the faces within one of its six (ReflectingFaces::areas).
        const uint64_t pairs = cells / 8 * (s.slots / 4);
        work.texelsRead +=
            cells * 8 + (perSample > 0.0f ? cells / 8 * 18 : 0) + pairs * (marched ? n / 4 : 0);
        work.texelsWritten += cells * 3;
        work.aluOps += pairs * (90 + 10 * uint64_t(marched ? n / 4 : 0));
        work.bytesMoved += cells * 48 + pairs * 48 / 8;
    }
    if (first) { // no light reaches the cascade: the injection volume is written all the same
        u.grid = glm::ivec4(int(n), 0, 0, 0);
        u.params = glm::vec4(0.0f, 0.0f, perSample, float(faces.areaStamp));
        u.vpls = glm::ivec4(0, 0, int(room_), int(parity_));
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindStorageBuffer(4, sources.front().vpls);
        cmd.dispatch(groups, groups, groups);
    }
    work.cells = cells;
    return work;
}

engine::WorkCounts GatheredReflection::recordFromList(rhi::CommandList& cmd, LpvVolumes& into,
                                                      const GeometryVolume& geometry,
                                                      const ReflectingFaces& faces, const VolumeGrid& grid,
                                                      const GatheredReflection& source) {
    if (!fromList_) throw std::logic_error("GatheredReflection::recordFromList: not made fromList");
    if (!source.listed() || source.room_ != room_)
        throw std::logic_error("GatheredReflection::recordFromList: the source has no list of this size");
    const uint32_t n = grid.size;
    const uint32_t groups = (n + 3) / 4;
    ReflectGatheredUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    const bool marched = faces.marched;
    u.grid = glm::ivec4(int(n), 0, marched ? 1 : 0, int(source.parity()));
    // The listed flux holds gi.intensity already; a face counts as a disk of its area.
    u.params = glm::vec4(1.0f, grid.cellSize * grid.cellSize / glm::pi<float>(), areaWeight(faces),
                         float(faces.areaStamp));
    bindFrame(cmd, into, geometry, faces);
    u.vpls = glm::ivec4(0, 0, int(room_), int(parity_));
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindStorageBuffer(4, source.list_);
    cmd.bindTexture(9, source.faceSlots_, pointSampler_);
    cmd.dispatch(groups, groups, groups);
    // An estimate: an eighth of the cells hold a surface; each reads a sixteenth of the source's
    // faces (a face per cell with a surface) and the 27 cells around it, marched through about a
    // quarter of the grid's faces, and the areas of the faces within one of its six.
    const uint64_t cells = uint64_t(n) * n * n;
    const uint64_t pairs = cells / 8 * (cells / 8 / 16 + 27);
    engine::WorkCounts work;
    work.cells = cells;
    work.texelsRead = cells * 8 + cells / 8 * (27 + (faces.areas ? 18 : 0)) + pairs * (marched ? n / 4 : 0);
    work.texelsWritten = cells * 3;
    work.aluOps = pairs * (90 + 10 * uint64_t(marched ? n / 4 : 0));
    work.bytesMoved = cells * 48 + pairs * 48 / 8;
    return work;
}

} // namespace lpv::gi
