// Multiple bounces (gi.bounces, Kaplanyan & Dachsbacher 2010): light that the geometry volume
// blocks during propagation is reflected by its surfels (their albedo) back into the cell in front
// of them, half a cell from the surface so nothing lights itself, and propagated again as the next
// bounce; each bounce's light is added to the cascade's result.
//
// Per further bounce: reflect (lpv_reflect_body.glsl: previous bounce's light -> injection volume),
// propagate (LpvPropagation, with occlusion, into a scratch result), add (lpv_bounce_add_body.glsl).
// Reflection is linear, so reflecting a bounce's accumulated light once equals reflecting every
// iteration's light as the paper does inside propagation; a bounce then gets its own iterations.
// Energy: each bounce carries at most (largest albedo) x (blocked share) of the previous one, so the
// sum over bounces is bounded by the first bounce / (1 - albedo).
#pragma once

#include "gi/LpvPropagation.h"
#include "gi/LpvVolumes.h"

namespace lpv::gi {

class GeometryVolume;

class MultipleBounces {
public:
    // Scratch for one bounce's light (3 SH textures in gi.sh_format), shared by every cascade.
    MultipleBounces(rhi::Device& device, const LpvSettings& settings, const LpvVolumes& volumes);
    ~MultipleBounces();
    MultipleBounces(const MultipleBounces&) = delete;
    MultipleBounces& operator=(const MultipleBounces&) = delete;

    // Adds bounces 2..`bounces` to `result` (the cascade's first-bounce light, just propagated in
    // `volumes` with `geometry`'s faces), each propagated `iterations` times by `propagation`.
    // Overwrites the injection volume.
    void record(rhi::CommandList& cmd, LpvVolumes& volumes, LpvPropagation& propagation,
                const GeometryVolume& geometry, uint32_t bounces, uint32_t iterations,
                const std::array<rhi::TextureHandle, 3>& result);

private:
    rhi::Device& device_;
    LpvSettings settings_;
    std::array<rhi::TextureHandle, 3> bounce_{};
    rhi::ComputePipelineHandle reflectPipeline_, addPipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
