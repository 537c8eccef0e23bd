// The scene's surfaces at the cell faces of the gathered cascades: what gi.gather's visibility
// marches through (vpl_visibility.glsl), in place of the geometry volume's faces, which hold only
// what the sun's RSM or the camera sees. A box's hidden sides and top let the light of a lit floor
// through to the walls behind it, and the sunlit ground outside a room reached its inside through
// the walls the camera does not see (docs/gi-fidelity.md).
//
// The scene is drawn once along each axis, orthographically onto a cascade's cells: a fragment at
// cell column (u, v) lies where a surface crosses the column's centre line, between the centres
// of two cells along the axis, and marks the face between them (the lower face of the cell above)
// as blocked. Along all three axes, a surface at an angle to the cells also closes the risers of
// its staircase, which a segment crossing it diagonally would slip through. A face holds the
// stamp of the pass that marked it, so no clear precedes a pass: a face is blocked where it holds
// the cascade's last stamp (stamp()). When the stamps run out (a million passes) every face is
// cleared once and they start again. A face also holds where its surface lies off it (up to half a
// cell), and blocks only a segment that reaches the surface: a point between a surface and its
// face (the floor at the foot of a wall whose face is in front of the wall) is on the surface's
// side, where it saw nothing of the room through that face as the cells fell.
//
// The three axes are one multi-draw (each draw's axis in its instance's draw index): two draws
// storing to one image would be a hazard to the RHI, a barrier between them; each cascade has its
// own faces and target for the same reason.
//
// Each column is drawn as kSamplesPerSide^2 samples, the middle one on its centre line (the one
// that marks), and every sample adds to its face's area (areas()): how much of the face a surface
// covers, which the further bounces' reflection takes as a face's reflecting share at most. The
// geometry volume's coverage, centred on the cells' corners, spreads a surface's rim over the
// faces of every cell around the corner, and those beyond the rim, where no surface is,
// reflected the light that reached them (docs/gi-fidelity.md).
#pragma once

#include "engine/render/MultiDraw.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <array>
#include <cstdint>

namespace lpv::engine {
class GpuScene;
}

namespace lpv::gi {

class SurfaceVoxels {
public:
    // The cascades, finest first, whose faces it keeps (VplGather::kCascades).
    static constexpr uint32_t kCascades = 3;
    // Samples along each side of a cell column; odd, so that the middle one is on its centre line.
    static constexpr uint32_t kSamplesPerSide = 3;

    // The bits of an area's count under its stamp (areas()); the stamps run below kStampLimit. The
    // shaders' is surface_areas.glsl's (the areas' test decodes their counts with this one).
    static constexpr uint32_t kAreaCountBits = 12;
    // The bits of a face's plane under its stamp (faces()); the shaders' is surface_faces.glsl's.
    static constexpr uint32_t kPlaneBits = 12;
    static constexpr uint32_t kStampLimit =
        1u << (32 - (kAreaCountBits > kPlaneBits ? kAreaCountBits : kPlaneBits));

    // For cascades of `gridSize` cells a side; `stampLimit` (at most kStampLimit) lower for a
    // test of the stamps' wrap.
    SurfaceVoxels(rhi::Device& device, uint32_t gridSize, uint32_t stampLimit = kStampLimit);
    ~SurfaceVoxels();
    SurfaceVoxels(const SurfaceVoxels&) = delete;
    SurfaceVoxels& operator=(const SurfaceVoxels&) = delete;

    // What it allocates for cascades of `gridSize` cells a side (GiBudget plans it).
    static uint64_t bytes(uint32_t gridSize);

    // Marks the faces of cascade `cascade` (< kCascades) at `grid` that the scene's surfaces cross:
    // the draws whose bounds reach the grid, at a level of detail within a quarter cell. Returns
    // the triangles drawn (three times each, one per axis). A scene with another number of draws
    // than the last one's makes the draws' axis stream anew (once per scene).
    uint64_t record(rhi::CommandList& cmd, const engine::GpuScene& scene, const VolumeGrid& grid,
                    uint32_t cascade);

    // Cascade c's faces, r32ui, (3 n) x n x n: the lower face along axis a of cell (x, y, z) at
    // texel (3 x + a, y, z), blocked where it holds stamp(c) above the low kPlaneBits; in them
    // where the surface crosses the face's column, (its offset from the face, in cells, + 1/2) x
    // 2^kPlaneBits, the highest where several cross it.
    rhi::TextureHandle faces(uint32_t cascade) const { return faces_.at(cascade); }
    // The stamp of cascade c's last record(); 0 before the first (no face is blocked).
    uint32_t stamp(uint32_t cascade) const { return stamps_.at(cascade); }
    // Cascade c's face areas, r32ui, laid out as faces(): above the low kAreaCountBits the stamp
    // of the pass that last counted the face, in them the samples of the surfaces that cross it,
    // kSamplesPerSide^2 to a face's area (more where surfaces overlap). A face holding another
    // stamp than stamp(c) has none.
    rhi::TextureHandle areas(uint32_t cascade) const { return areas_.at(cascade); }

private:
    rhi::Device& device_;
    uint32_t gridSize_;
    std::array<rhi::TextureHandle, kCascades> faces_;
    std::array<rhi::TextureHandle, kCascades> areas_;
    std::array<rhi::TextureHandle, kCascades> targets_; // the passes' colour targets, never written
    // Per draw d and axis a, at a x draws + d: d | a << 30 (the draw index stream's format).
    rhi::BufferHandle axisDraws_;
    uint32_t axisDrawsFor_ = 0; // draws
    rhi::GraphicsPipelineHandle pipeline_;
    engine::MultiDraw multiDraw_;
    std::array<uint32_t, kCascades> stamps_{};
    uint32_t lastStamp_ = 0;
    uint32_t stampLimit_ = kStampLimit;
};

} // namespace lpv::gi
