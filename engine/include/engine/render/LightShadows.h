// Shadow maps for the spot and point lights the lighting pass lights itself (render.spot_shadows,
// render.point_shadows). Without them such a light shines through walls. In a frame of many lights
// only the few that matter most to the camera get a map: a perspective view around a spot's cone,
// or six 90-degree views (a cube) around a point light. All views are tiles of one depth atlas, so
// the lighting pass binds one texture and compares against the tile of the light (a point light:
// the face its pixel lies in) with a 3x3 PCF, as it does for the sun. The atlas is made on a
// settings or scene change, never in a steady-state frame; choosing and drawing allocate nothing.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/GpuScene.h"
#include "engine/render/MultiDraw.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <span>

namespace lpv::engine {

// std140 block `LightShadows` of lighting.frag.
struct LightShadowUniforms {
    static constexpr uint32_t kMaxSpots = 4, kMaxPointLights = 2;
    static constexpr uint32_t kMaxLights = kMaxSpots + kMaxPointLights;
    static constexpr uint32_t kMaxViews = kMaxSpots + 6 * kMaxPointLights;
    std::array<glm::mat4, kMaxViews> viewProjection{};
    std::array<glm::vec4, kMaxViews> tile{}; // the view's tile in the atlas: xy its corner, zw its size (uv)
    // Per light with a map: x its index in the lighting pass's list, y its first view, z its views
    // (1 for a spot, 6 for a point light: +x, -x, +y, -y, +z, -z).
    std::array<glm::ivec4, kMaxLights> light{};
    // Per light: x a texel's side at 1 m from the light (2 tan(half angle) / tile side), for the
    // normal offset that keeps lit surfaces from shadowing themselves.
    std::array<glm::vec4, kMaxLights> params{};
    glm::ivec4 count{0}; // x: lights with a map this frame
};

// The view-projection of a square perspective depth map from `light` (a spot's record) along its
// axis, wide enough for its cone, reaching its range (or `reach` m for an infinite one).
glm::mat4 spotShadowViewProjection(const GpuPunctualLight& light, float reach);
// Face `face` (+x, -x, +y, -y, +z, -z) of a point light's cube of shadow views: a little wider
// than 90 degrees (`tanHalfAngle`), so a pixel's 3x3 PCF stays on the face its direction picks.
glm::mat4 pointShadowFaceViewProjection(const GpuPunctualLight& light, uint32_t face, float tanHalfAngle,
                                        float reach);

class LightShadows {
public:
    static constexpr uint32_t kMaxSpots = LightShadowUniforms::kMaxSpots;
    static constexpr uint32_t kMaxPointLights = LightShadowUniforms::kMaxPointLights;
    static constexpr uint32_t kTilesPerRow = 4;
    // A light that had a map last frame keeps it until another matters this much more: two lights
    // of near-equal importance at the last place would otherwise trade the map back and forth as
    // the camera moves, and their shadows pop on and off from frame to frame.
    static constexpr float kKeepFactor = 1.5f;

    explicit LightShadows(rhi::Device& device);
    ~LightShadows();
    LightShadows(const LightShadows&) = delete;
    LightShadows& operator=(const LightShadows&) = delete;

    // Makes the atlas for `spots` spots and `pointLights` point lights with tiles of `tileSize`^2
    // (none when both are 0), replacing the previous one. A settings or scene change, not a
    // steady-state frame: call it only when one of them differs.
    void resize(uint32_t spots, uint32_t pointLights, uint32_t tileSize);
    uint32_t spotCapacity() const { return spots_; }
    uint32_t pointLightCapacity() const { return pointLights_; }
    uint32_t tileSize() const { return tileSize_; }

    // Chooses this frame's lights among `lights` (the records the lighting pass lights, in its
    // order): the spots and, apart, the point lights that matter most to the camera, up to the
    // capacities. A light counts when its range reaches the camera's view; importance is its
    // intensity's luminance over the squared distance from the camera (at least 1 m^2), times
    // kKeepFactor for a light that had a map the frame before (by its index in `lights`), ties
    // kept in the lights' order. Then draws their views (every object in each view, full meshes);
    // returns the triangles drawn.
    uint64_t render(rhi::CommandList& cmd, const GpuScene& scene, std::span<const GpuPunctualLight> lights,
                    const CameraMatrices& camera, const Bounds& sceneBounds);
    // The lights with a map after the last render(), their views, and those of the views drawn:
    // a view that does not overlap the camera's is left cleared.
    uint32_t activeCount() const { return uint32_t(uniforms_.count.x); }
    uint32_t activeViews() const { return views_; }
    uint32_t drawnViews() const { return drawnViews_; }
    const LightShadowUniforms& uniforms() const { return uniforms_; }
    // The atlas, or `fallback` (any sampled depth texture) when there is none: the lighting pass's
    // binding must hold a texture, and it samples none while no light has a map.
    rhi::TextureHandle atlas(rhi::TextureHandle fallback) const { return atlas_ ? atlas_ : fallback; }
    // The work of the last render(), for the profiler.
    WorkCounts work() const { return work_; }

private:
    void release();
    // Places view `view`'s tile and, with `draw`, draws `scene` into it.
    uint64_t drawView(rhi::CommandList& cmd, const GpuScene& scene, uint32_t view, bool draw);

    rhi::Device& device_;
    uint32_t spots_ = 0, pointLights_ = 0, tileSize_ = 0, views_ = 0, drawnViews_ = 0;
    rhi::TextureHandle atlas_;
    uint32_t atlasWidth_ = 0, atlasHeight_ = 0;
    rhi::GraphicsPipelineHandle pipeline_;
    LightShadowUniforms uniforms_;
    WorkCounts work_;
    // The lights (indices into render()'s list) that got a map in the last render().
    std::array<uint32_t, LightShadowUniforms::kMaxLights> kept_{};
    uint32_t keptCount_ = 0;
    MultiDraw draws_;
};

} // namespace lpv::engine
