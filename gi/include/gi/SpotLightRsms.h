// Spot and point lights with a reflective shadow map of their own (gi.light_rsms spots,
// gi.point_light_rsms point lights; Kaplanyan 2009: "several lights inject into one shared
// volume"). Each frame the lights that matter most to the volume get a perspective RSM around a
// spot's cone, or a cube of six 90-degree faces around a point light, rendered once (not per
// cascade: the fit follows the light, not the volume) and clustered into VPL buffers of their own
// (one per RSM); the LPV injects those VPLs into every cascade after the sun's, so the light's
// bounce carries the colour of what it hits and propagates (and is occluded) like the sun's. The
// lighting pass lights these lights per pixel; the others stay analytic (PointLightInjection).
// RSMs and buffers are made with the volumes, never in a frame.
#pragma once

#include "engine/render/GpuScene.h"
#include "engine/scene/Scene.h"
#include "gi/AnalyticLight.h"
#include "gi/GeometryVolume.h"
#include "gi/LpvInjection.h"
#include "gi/LpvSettings.h"
#include "gi/ReflectiveShadowMap.h"
#include "gi/VplClustering.h"
#include "rhi/Device.h"

#include <array>
#include <memory>
#include <optional>
#include <span>

namespace lpv::gi {

class SpotLightRsms {
public:
    static constexpr uint32_t kMaxLights = 4;      // gi.light_rsms' upper limit
    static constexpr uint32_t kMaxPointLights = 2; // gi.point_light_rsms' upper limit
    static constexpr uint32_t kMaxRsms = kMaxLights + kMaxPointLights * kCubeFaces;

    // settings.lightRsms + 6 x settings.pointLightRsms RSMs of settings.rsmSize, each with a buffer
    // of spotLightVplSide(settings)^2 VPLs.
    SpotLightRsms(rhi::Device& device, const LpvSettings& settings);
    ~SpotLightRsms();
    SpotLightRsms(const SpotLightRsms&) = delete;
    SpotLightRsms& operator=(const SpotLightRsms&) = delete;

    // Picks this frame's spot and point lights (selectRsmLights) for the volume `reach` (the
    // coarsest cascade: every cascade lies inside it). Call before the renderer asks selected().
    void select(std::span<const engine::Light> lights, const VolumeGrid& reach);
    // True when light `index` of the lights given to select() has an RSM this frame.
    bool selected(uint32_t index) const;
    // The chosen lights (indices into the lights given to select()): spots, then point lights.
    std::span<const uint32_t> selection() const { return {selection_.data(), count_ + pointCount_}; }
    // RSMs drawn this frame: one per chosen spot, six per chosen point light.
    uint32_t rsmCount() const { return rsmCount_; }

    // Draws every selected light's RSM(s) and clusters each into its VPLs; returns the triangles
    // drawn. `specularAlbedo`: as ReflectiveShadowMap::record().
    uint64_t record(rhi::CommandList& cmd, const engine::GpuScene& scene, rhi::TextureHandle specularAlbedo,
                    std::span<const engine::Light> lights);
    // The VPL buffers of the RSMs drawn, for LpvInjection with the sun's (record() fills them).
    std::span<const VplSource> sources() const { return {sources_.data(), rsmCount_}; }
    // Those of sources() whose RSM can hold part of `grid` (a cascade: the light's range sphere and
    // the RSM's frustum, a spot's or a cube face's, both meet the box), copied to `out`; returns how
    // many. A cascade gets no VPLs that cannot land in it.
    uint32_t sourcesReaching(const VolumeGrid& grid, std::span<VplSource> out) const;
    // The same RSMs' VPLs as surfels for the geometry volume of `grid`.
    uint32_t surfelsReaching(const VolumeGrid& grid, std::span<PointLightSurfels> out) const;

private:
    // Whether RSM `slot` can hold part of `grid`, whose box is `box`.
    bool reaches(uint32_t slot, const VolumeGrid& grid, const engine::Bounds& box) const;
    // Copies the entries of `all` (one per RSM slot) whose RSM reaches `grid` into `out`.
    template <typename T>
    uint32_t copyReaching(const VolumeGrid& grid, std::span<const T> all, std::span<T> out) const;

    rhi::Device& device_;
    LpvSettings settings_;
    uint32_t capacity_ = 0, pointCapacity_ = 0; // lights
    std::array<std::unique_ptr<ReflectiveShadowMap>, kMaxRsms> rsms_;
    std::array<rhi::BufferHandle, kMaxRsms> vpls_{};
    std::array<uint32_t, kMaxLights + kMaxPointLights> selection_{};
    std::array<VplSource, kMaxRsms> sources_{};
    std::array<AnalyticLight, kMaxRsms> reach_{}; // each RSM's light's range, for sourcesReaching()
    std::array<glm::mat4, kMaxRsms> frusta_{};    // each RSM's view-projection, for sourcesReaching()
    std::array<PointLightSurfels, kMaxRsms> surfels_{};
    uint32_t count_ = 0, pointCount_ = 0, rsmCount_ = 0;
    VolumeGrid reachGrid_;                    // the volume the lights were chosen for
    std::optional<VplClustering> clustering_; // with any RSM
};

// Side of a spot light RSM's VPL grid: half the sun's (blocks of twice the texels, a quarter of
// the VPLs) when that divides the RSM. The sun's RSM spreads gi.vpl_count VPLs over the bounding
// square of a whole cascade; a spot's covers its cone, a fraction of that, so a quarter of them is
// still denser on the surfaces it lights, and the injection, which draws every VPL once per slice,
// pays a quarter of the sun's for it.
uint32_t spotLightVplSide(const LpvSettings& settings);
inline uint32_t spotLightVplCount(const LpvSettings& settings) {
    return spotLightVplSide(settings) * spotLightVplSide(settings);
}
// The VPL slots of a spot light RSM's buffer: kVplsPerCluster per block.
inline uint32_t spotLightVplSlots(const LpvSettings& settings) {
    return spotLightVplCount(settings) * kVplsPerCluster;
}

// How many of `lights` are of `type`.
uint32_t lightCount(std::span<const engine::Light> lights, engine::LightType type);

// The lights of `type` in `lights` that matter most to the volume at `grid`, at most `out.size()` of
// them, as indices into `lights`, most important first; returns how many. A light counts when its
// range reaches the volume and it is not dark; importance is its intensity's luminance over the
// squared distance from the volume's centre, no less than the squared half-extent (so the lights
// inside the volume rank by intensity alone). Ties keep the lights' order: the choice is
// deterministic and stable from frame to frame while nothing moves.
uint32_t selectRsmLights(std::span<const engine::Light> lights, engine::LightType type,
                         const VolumeGrid& grid, std::span<uint32_t> out);

} // namespace lpv::gi
