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

#include <glm/vec3.hpp>

#include <memory>

namespace lpv::gi {

class GeometryVolume;

class MultipleBounces {
public:
    // Scratch for one bounce's light (3 SH textures in gi.sh_format), shared by every cascade.
    // `keepFirst` (gi.cascades_together): the finest cascade's first bounce is kept apart (first()),
    // and the bounces have volumes of their own (ownVolumes()), so that a bounce can propagate with
    // the cascades from the first bounce of the frame before (LightPropagationVolume); those
    // have no partial sums where the propagation keeps them (`partialSums` false).
    MultipleBounces(rhi::Device& device, const LpvSettings& settings, const LpvVolumes& volumes,
                    bool keepFirst = false, bool partialSums = true);
    ~MultipleBounces();
    MultipleBounces(const MultipleBounces&) = delete;
    MultipleBounces& operator=(const MultipleBounces&) = delete;

    // Adds bounces 2..`bounces` to `result` (the cascade's first-bounce light, just propagated in
    // `volumes` with `geometry`'s faces), each propagated `iterations` times by `propagation`.
    // Overwrites the injection volume. With `first`: the first bounce is there, and `result`
    // becomes first + the further bounces. `reflected`: the caller has written the second
    // bounce's injection already (GatheredReflection). `keepSecond`: `result` is written there too
    // when it holds the first and second bounces.
    void record(rhi::CommandList& cmd, LpvVolumes& volumes, LpvPropagation& propagation,
                const GeometryVolume& geometry, uint32_t bounces, uint32_t iterations,
                const std::array<rhi::TextureHandle, 3>& result,
                const std::array<rhi::TextureHandle, 3>* first = nullptr, bool reflected = false,
                const std::array<rhi::TextureHandle, 3>* keepSecond = nullptr);

    // One more bounce whose injection the caller has written (GatheredReflection::recordFromList):
    // propagated, added to `result` and, with `keep`, written there too.
    void recordFurther(rhi::CommandList& cmd, LpvVolumes& volumes, LpvPropagation& propagation,
                       const GeometryVolume& geometry, uint32_t iterations,
                       const std::array<rhi::TextureHandle, 3>& result,
                       const std::array<rhi::TextureHandle, 3>* keep = nullptr);
    // The steps of one further bounce, for a caller that propagates it with other volumes:
    // reflect `source` (its cell c + `shift` lighting cell c) into `into`'s injection volume...
    void recordReflect(rhi::CommandList& cmd, LpvVolumes& into, const GeometryVolume& geometry,
                       const std::array<rhi::TextureHandle, 3>& source, glm::ivec3 shift = glm::ivec3(0));
    // ... propagate it (into bounce()) ...
    PropagationJob job(LpvVolumes& volumes, const GeometryVolume& geometry);
    // ... and add it to `result`, or make `result` `*first` + it; with `keep`, written there too.
    void recordAdd(rhi::CommandList& cmd, LpvVolumes& volumes,
                   const std::array<rhi::TextureHandle, 3>& result,
                   const std::array<rhi::TextureHandle, 3>* first = nullptr,
                   const std::array<rhi::TextureHandle, 3>* keep = nullptr);

    // keepFirst: the finest cascade's first bounce, and the volumes the bounces propagate in.
    const std::array<rhi::TextureHandle, 3>* first() const { return own_ ? &first_ : nullptr; }
    LpvVolumes* ownVolumes() { return own_.get(); }

private:
    rhi::Device& device_;
    LpvSettings settings_;
    std::unique_ptr<LpvVolumes> own_; // keepFirst; its accumulated() is bounce_
    std::array<rhi::TextureHandle, 3> bounce_{}, first_{};
    rhi::ComputePipelineHandle reflectPipeline_, addPipeline_, addFirstPipeline_;
    rhi::ComputePipelineHandle addKeepPipeline_, addFirstKeepPipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
