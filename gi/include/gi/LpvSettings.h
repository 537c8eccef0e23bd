// The GI's settings, a plain struct the game fills and hands to LightPropagationVolume::update()
// each frame; every one can change while the game runs (volumes are remade on the next frame when a
// size changes). The engine's adapter (gi/adapter/LpvConfig.h) reads them from gi.* in TOML and
// --set; the names in the comments are those keys.
#pragma once

#include "gi/FogSettings.h"
#include "gi/GiBudgetPolicy.h"
#include "rhi/Format.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace lpv::gi {

enum class ShFormat { Rgba8, Rgba16f, Rgba32f };
enum class GiDebugView { None, VolumeSlice, Vpls, Indirect };

struct LpvSettings {
    bool enabled = false;
    uint32_t gridSize = 32;
    float cellSize = 0.25f; // of the finest cascade; each further cascade doubles it
    // gi.cell_size = auto: the GI sizes the finest cascade to the open space around the camera
    // (engine::OpenSpace) each frame, and cellSize is what it chose.
    bool cellSizeAuto = false;
    uint32_t cascades = 3;
    // Frames between two updates of each coarse cascade (GiLoad::coarseUpdateInterval); under
    // gi.budget_policy=adapt the scheduler starts here.
    uint32_t coarseUpdateInterval = 1;
    uint32_t iterations = 8;
    uint32_t rsmSize = 256;
    // Geometric error an RSM may draw with, in its texels (engine::GpuDraw::lodWithin); 0: full meshes.
    float rsmLodTexels = 0.5f;
    uint32_t vplCount = 4096;
    float intensity = 1.0f;
    ShFormat shFormat = ShFormat::Rgba16f;
    GiDebugView debugView = GiDebugView::None;
    // The volume slice gi.debug_view=volume_slice shows; none chosen: slice 16, or the last one of
    // a smaller volume (a chosen slice outside the volume is refused).
    std::optional<uint32_t> debugSlice;
    float rgba8Range = 12.0f;
    bool damping = true;
    bool occlusion = true; // geometry volume attenuates propagation
    // With occlusion: the coarse cascades' lookups keep to their open faces too (the finest's always).
    bool lookupOcclusion = true;
    // With occlusion: the coarse cascades' geometry volumes take the camera's samples too, as the
    // areas of surface they stand for (the finest's always takes them, as marks).
    bool coarseCameraOcclusion = true;
    // Whether the geometry volume keeps the coarse cascades' camera areas.
    bool cameraAreas() const { return occlusion && coarseCameraOcclusion && cascades > 1; }
    // gi.cascades_together: every cascade gets an injection volume and partial sums of its own, so
    // all cascades propagate in the same dependent steps; a finer one then takes the light from
    // beyond its border from the coarser one's result of the frame before.
    bool cascadesTogether = true;
    // Whether they do: it also needs a face volume per cascade (the propagations run after every
    // geometry volume is built), the further bounces in the finest cascade only (the surfels'
    // albedo is the last built's), and float volumes (rgba8 notes clipping in one set).
    bool propagateTogether() const {
        return cascadesTogether && cascades > 1 && (!occlusion || lookupOcclusion) && bounceCascades <= 1 &&
               shFormat != ShFormat::Rgba8;
    }
    bool glossy = true; // glossy reflections marched through the volume
    // Surfaces this rough or rougher get no glossy march (lpv_glossy.glsl's glossyFade).
    float glossyMaxRoughness = 1.0f;
    // The finest cascades' first bounce gathered per pixel from their VPLs (gi/VplGather.h)
    // instead of read from the propagated volume: gi.gather as configured, and whether it runs,
    // which LightPropagationVolume decides for Auto from its device and platform (gathers()).
    enum class Gather : uint8_t { Auto, On, Off };
    Gather gatherMode = Gather::Auto;
    bool gather = false;
    uint32_t bounces = 1; // light reflected off the geometry volume's surfels (needs occlusion)
    // The finest cascades that add the further bounces; coarser ones carry the first bounce only.
    uint32_t bounceCascades = 1;
    // Whether cascade c (0 = finest) adds the further bounces.
    bool bouncesIn(uint32_t c) const { return bounces > 1 && c < bounceCascades; }
    GiBudgetPolicy budgetPolicy = GiBudgetPolicy::Fixed;
    // gi.analytic_lights: the volume carries the point and spot lights (PointLightInjection).
    bool analyticLights = true;
    // Spot lights with a reflective shadow map of their own (SpotLightRsms).
    uint32_t lightRsms = 1;
    // Point lights with a cube RSM of their own (six faces, SpotLightRsms).
    uint32_t pointLightRsms = 1;
    // Per axis, 1/resolutionDivisor of the frame's pixels get a lookup and a glossy march; the
    // lighting pass rebuilds the rest (engine::IndirectLighting::resolutionDivisor).
    uint32_t resolutionDivisor = 2;
    // The participating medium the volume lights (fog.*); it runs with GI off too, lit by the sun.
    FogSettings fog;

    // Face transmittance volumes the geometry volume keeps (GeometryVolume's face slots): one per
    // cascade when every cascade's lookup reads its own, else the one the finest cascade builds last.
    uint32_t faceVolumes() const { return occlusion ? (lookupOcclusion ? cascades : 1) : 0; }
    // Side of the VPL grid the RSM is clustered into (sqrt of vplCount).
    uint32_t vplGridSide() const;
    // VPL slots of the sun's RSM: each of the vplCount blocks has kVplsPerCluster.
    uint32_t vplSlots() const;
    bool operator==(const LpvSettings&) const = default;
};

// A block of RSM texels clusters into up to this many VPLs (vpl_cluster.comp): one per depth layer
// when the block spans a depth edge, the second slot left empty otherwise. Buffers, draws and
// budgets count slots.
inline constexpr uint32_t kVplsPerCluster = 2;

// gi.vpl_count's range.
inline constexpr uint32_t kMinVplCount = 16, kMaxVplCount = 262144;

// A setting at odds with another: the one refused, the one it contradicts (empty: none) and why,
// in a sentence that names both.
struct LpvSettingsError {
    std::string_view setting; // "gi.vpl_count"
    std::string_view related; // "gi.rsm_size"
    std::string message;
};

// Cross-checks the settings (vpl count against RSM size, bounces against occlusion, a chosen debug
// slice against the grid size); nothing when they hold together. No heap unless there is an error.
std::optional<LpvSettingsError> validateLpvSettings(const LpvSettings& settings);

std::string_view shFormatName(ShFormat f);
rhi::Format shTextureFormat(ShFormat f);

} // namespace lpv::gi
