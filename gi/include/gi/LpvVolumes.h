// The light propagation volume itself: injection of VPLs into a float volume (points drawn per
// slice with additive blending), then N propagation iterations ping-ponging between two volumes
// and accumulating into a third, all in gi.sh_format. Three SH textures (R, G, B) per volume.
#pragma once

#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "rhi/Device.h"

#include <array>

namespace lpv::gi {

class LpvVolumes {
public:
    LpvVolumes(rhi::Device& device, const LpvSettings& settings);
    ~LpvVolumes();
    LpvVolumes(const LpvVolumes&) = delete;
    LpvVolumes& operator=(const LpvVolumes&) = delete;

    // True when these volumes were made for the sizes and format of `settings`.
    bool matches(const LpvSettings& settings) const;

    // Clears the injection volume and adds `vplCount` VPLs from `vpls` (std430 array of
    // {vec4 position (w: valid), vec4 normal, vec4 flux}).
    void inject(rhi::CommandList& cmd, rhi::BufferHandle vpls, uint32_t vplCount, const VolumeGrid& grid,
                glm::vec3 lightDirection, float intensity);
    // Propagates `iterations` times from the injection volume, accumulating into accumulated().
    void propagate(rhi::CommandList& cmd, uint32_t iterations);

    const std::array<rhi::TextureHandle, 3>& injected() const { return inject_; }
    const std::array<rhi::TextureHandle, 3>& accumulated() const { return accum_; }
    bool encoded() const { return settings_.shFormat == ShFormat::Rgba8; }
    float encodeRange() const { return settings_.rgba8Range; }
    uint32_t gridSize() const { return settings_.gridSize; }

private:
    rhi::Device& device_;
    LpvSettings settings_;
    std::array<rhi::TextureHandle, 3> inject_, ping_, pong_, accum_;
    rhi::GraphicsPipelineHandle injectPipeline_;
    rhi::ComputePipelineHandle propagatePipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
