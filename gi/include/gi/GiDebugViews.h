// The GI's debug views (gi.debug_view), drawn over the finished frame: a z slice of the finest
// cascade's volume in a corner, or every VPL as a point where it lies, to see what the volume holds
// and where the light was injected from. gi.debug_view=indirect is the lighting pass's own.
#pragma once

#include "engine/render/CameraMatrices.h"
#include "gi/LpvInjection.h"
#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "gi/LpvVolumes.h"
#include "rhi/Device.h"

#include <cstdint>
#include <span>

namespace lpv::gi {

class GiDebugViews {
public:
    explicit GiDebugViews(rhi::Device& device);
    ~GiDebugViews();
    GiDebugViews(const GiDebugViews&) = delete;
    GiDebugViews& operator=(const GiDebugViews&) = delete;

    // Draws `view` over `output` (RGBA8 sRGB, kept): VolumeSlice shows z slice `slice` (clamped to
    // the grid) of `volumes.accumulated()`, placed at `grid`, as a square of half the output's
    // height in its top-left corner; Vpls draws the points of `vpls` (the sun's, then the lights'
    // with an RSM) as `camera` sees them. None and Indirect record nothing.
    void record(rhi::CommandList& cmd, GiDebugView view, const engine::CameraMatrices& camera,
                rhi::TextureHandle output, const LpvVolumes& volumes, const VolumeGrid& grid, uint32_t slice,
                std::span<const VplSource> vpls);

private:
    rhi::Device& device_;
    rhi::GraphicsPipelineHandle slicePipeline_, pointsPipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
