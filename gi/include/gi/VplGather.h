// The near field's first bounce gathered per pixel from the VPLs (gi.gather): a fullscreen pass
// at the lookup's resolution that sums, for every texel, the irradiance the VPLs of the finest
// cascades send it (flux x cos x cos / (pi r^2), Dachsbacher & Stamminger's RSM gather) in the
// share of the lookup those cascades answer for. The lookup then reads each such cascade's light
// less its propagated first bounce, and adds this gather averaged over 4 x 4 texels on the
// texel's surface (lpv_lookup.glsl, GATHER): the propagation scatters its first bounce within a
// few cells and leaves ceilings dark (docs/gi-fidelity.md), the gather places it; the volume keeps
// the further bounces, the coarse cascades, the glossy term and the fog.
//
// Interleaved: each texel of a 4 x 4 block sums a sixteenth of the VPLs (vpl_gather.frag).
// Visibility (gi.occlusion): each VPL-texel segment is marched through the cascade's cell faces,
// cell by cell, and stops at the first that a surface of the scene crosses (SurfaceVoxels).
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/IndirectLighting.h"
#include "gi/LpvReference.h"
#include "gi/VplWindows.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <span>

namespace lpv::gi {

// One set of VPLs (vpl_cluster.comp's layout: a square grid of clusters, two slots each).
struct GatherSource {
    rhi::BufferHandle vpls;
    uint32_t slots = 0;
    uint32_t side = 0; // the cluster grid's side: slots = 2 side^2
    // The sun's VPLs of this cascade (< kCascades), or -1: a spot or point light's, injected into
    // the cascades of `cascades` (bit c, c < kCascades).
    int32_t cascade = -1;
    uint32_t cascades = 0;
    // r^2 below this counts as this (m^2): about a cluster's area; `listed`: added to r^2, a face's
    // area over pi (a disk's form factor on its axis).
    float nearest = 0.0f;
    // Visibility: the faces of cascade `facesCascade` (SurfaceVoxels::faces(), blocked where they
    // hold `facesStamp`) marched between each VPL and texel; none: unmarched.
    rhi::TextureHandle faces;
    uint32_t facesCascade = 0;
    uint32_t facesStamp = 0;
    // The second bounce's VPLs (GatheredReflection): 16 lists, one per phase, each of room
    // `slots`, counted in counter set `side`; their flux holds gi.intensity already.
    bool listed = false;
    rhi::TextureHandle faceSlots; // listed: per cell its faces and their slots (r32ui)
    // The view-projection of the RSM the VPLs were clustered from: a texel sums the clusters over
    // its own point of that map and next to it whole (vpl_gather.frag); zero: none.
    glm::mat4 lightViewProjection{0.0f};
    // The sun's: where its VPLs are listed by window for the pixels (VplWindows::bytes(side));
    // none: each texel walks the whole grid.
    rhi::BufferHandle windows;
};

class VplGather {
public:
    // The cascades, finest first, whose share of the lookup is gathered: all of gi.cascades' default
    // 3. A cascade beyond them keeps its propagated first bounce, which reads a sunlit ground's
    // own light back above it; a fourth would take the lookup past the 32 fragment textures a GL
    // device may bind (IndirectLookup::kGatherTextureBindings). The shaders' is
    // gathered_cascades.glsl's.
    static constexpr uint32_t kCascades = 3;

    explicit VplGather(rhi::Device& device);
    ~VplGather();
    VplGather(const VplGather&) = delete;
    VplGather& operator=(const VplGather&) = delete;

    // Makes the target for lookup targets of this size (at a configuration or resize, not in a
    // steady frame); the bytes it holds.
    uint64_t resize(uint32_t width, uint32_t height);

    // Lists each sun source's VPLs by window (where it has `windows`), clears the target and adds
    // each source's gathered irradiance in its cascades' share.
    // `cascades`: every cascade's grid, finest first (the shares depend on how many there are);
    // `blendBand` as the lookup's; the target's texel t is G-buffer pixel t x divisor.
    void record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                const engine::GBufferView& gbuffer, std::span<const VolumeGrid> cascades, float blendBand,
                float intensity, uint32_t divisor, std::span<const GatherSource> sources);

    // RGBA16F at the lookup's resolution: the interleaved gather, rgb irradiance.
    rhi::TextureHandle gathered() const { return target_; }

private:
    rhi::Device& device_;
    rhi::GraphicsPipelineHandle pipeline_;
    VplWindows windows_;
    rhi::TextureHandle target_;
    rhi::TextureHandle noFaceSlots_; // bound where a draw sums no second bounce (r32ui, 1^3)
    rhi::TextureHandle noFaces_;     // bound where a draw is unmarched (r32ui storage, 1^3)
    rhi::SamplerHandle pointSampler_;
};

// Per texel and draw (a set of VPLs): its depth and normal; per texel a sixteenth of all `slots`,
// each marched through about `marchedFaces` faces (0 unmarched; an estimate: a march ends at the
// first wall).
engine::WorkCounts gatherWork(uint64_t pixels, uint64_t slots, uint64_t draws, uint32_t marchedFaces);

} // namespace lpv::gi
