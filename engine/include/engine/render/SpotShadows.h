// Shadow maps for the spot lights the lighting pass lights itself (render.spot_shadows). Without
// them a spot shines through walls: in a frame of many lights only the few that matter most to the
// camera get a perspective depth map around their cone each frame, and the lighting pass compares
// against it (3x3 PCF) as it does for the sun. Maps are made on a settings or scene change, never in
// a steady-state frame; choosing and drawing them allocates nothing.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/GpuScene.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <span>

namespace lpv::engine {

// std140 block `SpotShadows` of lighting.frag.
struct SpotShadowUniforms {
    static constexpr uint32_t kMaxMaps = 4;
    std::array<glm::mat4, kMaxMaps> viewProjection{};
    glm::ivec4 light{-1}; // per map: the index of its light in the lighting pass's list, -1 none
    // Per map: a texel's side at 1 m from the light (2 tan(half angle) / size), for the normal
    // offset that keeps lit surfaces from shadowing themselves.
    glm::vec4 texelAtMetre{0.0f};
};

// The view-projection of a square perspective depth map from `light` (a spot's record) along its
// axis, wide enough for its cone, reaching its range (or `reach` m for an infinite one).
glm::mat4 spotShadowViewProjection(const GpuPunctualLight& light, float reach);

class SpotShadows {
public:
    static constexpr uint32_t kMaxMaps = SpotShadowUniforms::kMaxMaps;

    explicit SpotShadows(rhi::Device& device);
    ~SpotShadows();
    SpotShadows(const SpotShadows&) = delete;
    SpotShadows& operator=(const SpotShadows&) = delete;

    // Makes `maps` depth maps of `size`^2 (none for 0), replacing the previous ones. A settings or
    // scene change, not a steady-state frame: call it only when one of them differs.
    void resize(uint32_t maps, uint32_t size);
    uint32_t mapCount() const { return maps_; }
    uint32_t size() const { return size_; }

    // Chooses this frame's lights among `lights` (the records the lighting pass lights, in its
    // order): the spots that matter most to the camera, at most mapCount() of them. A spot counts
    // when its range reaches the camera's view; importance is its intensity's luminance over the
    // squared distance from the camera (at least 1 m^2), ties kept in the lights' order. Then draws
    // their maps (every object in each map's view, full meshes); returns the triangles drawn.
    uint64_t render(rhi::CommandList& cmd, const GpuScene& scene, std::span<const GpuPunctualLight> lights,
                    const CameraMatrices& camera, const Bounds& sceneBounds);
    // The maps chosen by the last render(): how many, and what the lighting pass needs.
    uint32_t activeCount() const { return active_; }
    const SpotShadowUniforms& uniforms() const { return uniforms_; }
    // Map k, or `fallback` (any sampled depth texture) when map k was not drawn this frame: every
    // binding of the lighting pass must hold a texture, and it never samples those.
    rhi::TextureHandle map(uint32_t k, rhi::TextureHandle fallback) const {
        return k < active_ ? textures_[k] : fallback;
    }
    // The work of the last render(), for the profiler.
    WorkCounts work() const { return work_; }

private:
    void release();

    rhi::Device& device_;
    uint32_t maps_ = 0, size_ = 0, active_ = 0;
    std::array<rhi::TextureHandle, kMaxMaps> textures_{};
    rhi::GraphicsPipelineHandle pipeline_;
    SpotShadowUniforms uniforms_;
    WorkCounts work_;
};

} // namespace lpv::engine
