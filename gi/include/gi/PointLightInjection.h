// Many small point and spot lights in the LPV without an RSM each: every frame the lights that
// reach the volume are packed into a GPU buffer made once (kMaxLights of them), and one compute
// dispatch over the volume's cells adds each light, already propagated, to the accumulated SH
// volumes (the formula is in gi/AnalyticLight.h). It runs after the propagation, so the lights are
// not propagated a second time. Setting: gi.analytic_lights.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/scene/Scene.h"
#include "gi/AnalyticLight.h"
#include "gi/LpvSettings.h"
#include "gi/LpvVolumes.h"
#include "rhi/Device.h"

#include <array>
#include <span>

namespace lpv::gi {

class PointLightInjection {
public:
    // As many as the renderer's punctual-light buffer holds (engine::GpuScene::kMaxPunctualLights).
    static constexpr uint32_t kMaxLights = 1024;
    static constexpr uint64_t kBufferBytes = kMaxLights * sizeof(AnalyticLight);
    // A uniform block (see point_lights_body.glsl) that one CommandList::updateBuffer call fills.
    static_assert(kBufferBytes <= 65536);

    // Made with the volumes: the pipeline matches `settings.shFormat`.
    PointLightInjection(rhi::Device& device, const LpvSettings& settings);
    ~PointLightInjection();
    PointLightInjection(const PointLightInjection&) = delete;
    PointLightInjection& operator=(const PointLightInjection&) = delete;

    // Packs the point and spot lights of `lights` that reach `grid` (the first kMaxLights of them;
    // directional lights are the RSM's), scaled by `intensityScale` (gi.intensity), uploads them and
    // adds them to `result` (volumes.accumulated() when null): cascade `cascade`'s result, placed
    // at `grid`. Call after the propagation of every cascade (a coarser cascade's result is also
    // what the finer ones take in at their borders, and should not carry these lights then; a
    // coarse cascade kept from an earlier frame does, see LightPropagationVolume::renderIndirect).
    // `skip`: indices into `lights` left out (spot and point lights with an RSM of their own, SpotLightRsms).
    // Returns the lights added.
    uint32_t record(rhi::CommandList& cmd, std::span<const engine::Light> lights, LpvVolumes& volumes,
                    const VolumeGrid& grid, float intensityScale,
                    const std::array<rhi::TextureHandle, 3>* result = nullptr, uint32_t cascade = 0,
                    std::span<const uint32_t> skip = {});

    // What the last record() uploaded.
    std::span<const AnalyticLight> lights() const { return {staged_.data(), count_}; }
    // About how many (cell, light) pairs the last record() evaluates: per light, the cells of the
    // shader's 4x4x4 blocks that its range's bounding box overlaps (the shader tests the sphere).
    uint64_t cellEvaluations() const { return cellEvaluations_; }

private:
    rhi::Device& device_;
    rhi::Format format_;
    std::array<rhi::BufferHandle, 4> buffers_{}; // per cascade
    rhi::ComputePipelineHandle pipeline_;
    std::array<AnalyticLight, kMaxLights> staged_{};
    uint32_t count_ = 0;
    uint64_t cellEvaluations_ = 0;
};

// Work of one record() that added `lightCount` lights in `cellEvaluations` (cell, light) pairs.
engine::WorkCounts analyticLightsWork(const LpvSettings& s, uint32_t lightCount, uint64_t cellEvaluations);

} // namespace lpv::gi
