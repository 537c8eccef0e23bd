// Injection (Kaplanyan 2009): each VPL becomes a clamped-cosine SH lobe (intensity flux/pi) per
// colour channel, shifted half a cell along its normal and half a cell toward its light, added to
// its cell of the injection volume. The VPLs are points drawn with additive blending: in one
// layered draw where the vertex shader may pick the slice, else once per slice.
#pragma once

#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "gi/LpvVolumes.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <span>

namespace lpv::gi {

// One light's VPLs: a buffer of std430 {vec4 position (w: valid), vec4 normal, vec4 flux} and
// where its light is, for the half-cell shift toward it.
struct VplSource {
    rhi::BufferHandle vpls;
    uint32_t count = 0;
    // w 0: xyz is the direction a distant light travels (the sun); w 1: xyz is the position of a
    // light at a point (a spot or point light), each VPL's direction then runs from it.
    glm::vec4 light{0.0f, -1.0f, 0.0f, 0.0f};
    // The view-projection of the RSM they were clustered from, for the gather (GatherSource);
    // zero: not given.
    glm::mat4 viewProjection{0.0f};
};

class LpvInjection {
public:
    // For volumes made with `settings` (their size and format).
    LpvInjection(rhi::Device& device, const LpvSettings& settings);
    ~LpvInjection();
    LpvInjection(const LpvInjection&) = delete;
    LpvInjection& operator=(const LpvInjection&) = delete;

    // Clears the injection volume of `volumes` and adds the VPLs of every source (several lights
    // share the volume), all in one pass per slice, for the volume placed at `grid`. `cascade`:
    // whose record (Rgba8Clipping) the rgba8 encodes of what is propagated from this injection
    // note clipping in.
    void record(rhi::CommandList& cmd, LpvVolumes& volumes, std::span<const VplSource> sources,
                const VolumeGrid& grid, float intensity, uint32_t cascade = 0);
    // One distant light's `vplCount` VPLs from `vpls`, travelling along `lightDirection`.
    void record(rhi::CommandList& cmd, LpvVolumes& volumes, rhi::BufferHandle vpls, uint32_t vplCount,
                const VolumeGrid& grid, glm::vec3 lightDirection, float intensity);

private:
    rhi::Device& device_;
    uint32_t gridSize_;
    bool layered_; // one layered draw (rhi Caps::vertexShaderLayer)
    rhi::GraphicsPipelineHandle pipeline_;
};

} // namespace lpv::gi
