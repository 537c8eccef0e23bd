// Multiple bounces with gi.gather: the second bounce reflected from the first bounce gathered at
// the geometry volume's blocking faces, rather than from the propagated first bounce
// (MultipleBounces::recordReflect). The propagation scatters its first bounce within a few cells
// (docs/gi-fidelity.md), so the walls and ceilings far from the lit patches, which the gather now
// lights for the eye, reflected next to nothing; here each face receives what the VPLs send it
// (flux x cos x cos / (pi r^2), visibility marched through the faces as the per-pixel gather
// does), and its surfels reflect it into the cell in front of them as the next bounce's VPLs.
// lpv_reflect_gathered_body.glsl has the per-cell arithmetic. Made `fromList`, it reflects the
// third bounce from the second's listed faces the same way (recordFromList), and lists it in turn.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "gi/LpvSettings.h"
#include "gi/VplGather.h"
#include "gi/VplWindows.h"
#include "rhi/Device.h"

#include <span>

namespace lpv::gi {

class GeometryVolume;
class LpvVolumes;

// The faces that reflect: the geometry volume's, by their blocked share (marched through where
// `marched`), each at most the share a surface covers where `areas` is given (SurfaceVoxels::areas()).
struct ReflectingFaces {
    rhi::TextureHandle transmittance; // GeometryVolume::faceTransmittance()
    bool marched = false;
    rhi::TextureHandle areas; // none: the blocked share alone
    uint32_t areaStamp = 0;   // SurfaceVoxels::stamp() of the areas
    uint32_t areaSamples = 0; // of `areas` to a face's whole area
};

class GatheredReflection {
public:
    // For volumes of `gridSize` cells a side; `fromList`: recordFromList() rather than record().
    GatheredReflection(rhi::Device& device, ShFormat format, uint32_t gridSize, bool fromList = false);
    // What it allocates for volumes of `gridSize` cells a side: the lists of faces, one per phase
    // of 16 (room for a room's six sides twice and what stands in it, 48 bytes a face, after 32
    // counters), and a 32-bit slot a cell (GiBudget plans both).
    static constexpr uint32_t kPhases = kGatherPhases;
    static uint32_t roomFor(uint32_t gridSize) { return gridSize * gridSize; } // a phase's
    static uint64_t listBytes(uint32_t gridSize) {
        return 2 * kPhases * 4 + uint64_t(kPhases) * roomFor(gridSize) * 48;
    }
    static uint64_t slotBytes(uint32_t gridSize) { return uint64_t(gridSize) * gridSize * gridSize * 4; }
    ~GatheredReflection();
    GatheredReflection(const GatheredReflection&) = delete;
    GatheredReflection& operator=(const GatheredReflection&) = delete;

    // Writes `into`'s injection volume (grid `grid`) with what the faces `faces` (and the surfels'
    // albedo of `geometry`) reflect of the light of `sources`: those whose sun VPLs are of cascade
    // `cascade`, or that are injected into it.
    // The work it records (for the profiler and the console prediction).
    engine::WorkCounts record(rhi::CommandList& cmd, LpvVolumes& into, const GeometryVolume& geometry,
                              const ReflectingFaces& faces, const VolumeGrid& grid, uint32_t cascade,
                              float intensity, std::span<const GatherSource> sources);

    // The same from the faces `source` listed in its last record() (the next bounce), in one
    // dispatch. `source` must have recorded this frame.
    engine::WorkCounts recordFromList(rhi::CommandList& cmd, LpvVolumes& into, const GeometryVolume& geometry,
                                      const ReflectingFaces& faces, const VolumeGrid& grid,
                                      const GatheredReflection& source);

    // The reflecting faces of the last record() as VPLs of the second bounce, for the per-pixel
    // gather (VplGather): none before the first.
    rhi::BufferHandle listed() const { return recorded_ ? list_ : rhi::BufferHandle{}; }
    // Which of the lists' two sets of counters the last record() counted in.
    uint32_t parity() const { return parity_; }
    uint32_t room() const { return room_; } // each phase's list's
    // Per cell its listed faces and the slot of the first (r32ui; the gather sums the near ones).
    rhi::TextureHandle faceSlots() const { return faceSlots_; }

private:
    // A frame's record: flips the counters' set, binds the pipeline, the lists, the injection
    // volume, `faces` and the surfels' albedo.
    void bindFrame(rhi::CommandList& cmd, LpvVolumes& into, const GeometryVolume& geometry,
                   const ReflectingFaces& faces);

    rhi::Device& device_;
    uint32_t room_ = 0;
    rhi::BufferHandle list_;       // 2 x 16 counters, then 16 lists of room_ faces
    rhi::TextureHandle faceSlots_; // r32ui per cell: its first face's slot in list_
    rhi::TextureHandle noAreas_;   // r32ui, 1 texel: bound where ReflectingFaces has no areas
    bool recorded_ = false;
    bool fromList_ = false;
    uint32_t parity_ = 0;
    rhi::ComputePipelineHandle pipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
