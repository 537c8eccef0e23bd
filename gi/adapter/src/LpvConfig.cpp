// The gi.* and fog.* settings: their declarations (registered when this library is linked: TOML, --set and
// --help-config know them) and their reading into gi::LpvSettings.
#include "gi/adapter/LpvConfig.h"

#include <optional>
#include <string>

namespace lpv::gi {
namespace {

using engine::Apply;
const engine::BoolSetting kEnabled{"gi.enabled", false,
                                   "Dynamic global illumination (light propagation volumes)"};
const engine::IntSetting kGridSize{"gi.grid_size", 32, 16, 64, "LPV cells per axis"};
const engine::AutoFloatSetting kCellSize{
    "gi.cell_size", 0.25, 0.01, 100.0,
    "LPV cell size in metres of the finest cascade (volume = grid x cell); auto: sized so that the finest "
    "cascade spans the room around the camera (gi.grid_size - 4 cells across its largest side), or the scene "
    "where the camera stands in the open"};
const engine::IntSetting kCascades{"gi.cascades", 3, 1, 4,
                                   "Nested volumes, each twice the extent of the previous (cascaded LPV)"};
const engine::IntSetting kCoarseUpdateInterval{
    "gi.coarse_update_interval", 1, 1, 4,
    "Frames between two updates of each coarse cascade (all but the finest), which keep their last result "
    "in between and take turns; from 2 x (gi.cascades - 1) each update is split over two frames (its RSM, "
    "then its volume). gi.budget_policy=adapt starts from this value"};
const engine::IntSetting kIterations{"gi.iterations", 8, 1, 64, "Propagation iterations per frame"};
const engine::IntSetting kRsmSize{"gi.rsm_size", 256, 32, 2048,
                                  "Reflective shadow map resolution (texels per side)"};
const engine::FloatSetting kRsmLodTexels{
    "gi.rsm_lod_texels", 0.5, 0.0, 16.0,
    "Geometric error allowed in an RSM, in its texels: each object is drawn at the coarsest level of detail "
    "(simplified at load) that strays less; 0 draws every mesh in full"};
const engine::IntSetting kVplCount{
    "gi.vpl_count", 4096, kMinVplCount, kMaxVplCount,
    "VPLs after clustering the RSM (a square number whose side divides gi.rsm_size)"};
const engine::FloatSetting kIntensity{"gi.intensity", 1.0, 0.0, 100.0, "Scale of the indirect light"};
const engine::EnumSetting<ShFormat> kShFormat{
    "gi.sh_format",
    ShFormat::Rgba16f,
    {{ShFormat::Rgba8, "rgba8"}, {ShFormat::Rgba16f, "rgba16f"}, {ShFormat::Rgba32f, "rgba32f"}},
    "Storage of the SH volumes; the platform profile limits it"};
const engine::EnumSetting<GiDebugView> kDebugView{
    "gi.debug_view",
    GiDebugView::None,
    {{GiDebugView::None, "none"},
     {GiDebugView::VolumeSlice, "volume_slice"},
     {GiDebugView::Vpls, "vpls"},
     {GiDebugView::Indirect, "indirect"}},
    "GI debug view: a volume slice, the VPLs, or the indirect light alone"};
// A radiance, so one value fits every cascade and cell size (LpvVolumes::encodeRange). 12 keeps the
// mean indirect light of the Cornell box, the atrium and the lights hall within 1% of rgba16f's
// (640x360; the tests hold them within 3% at 320x240).
const engine::FloatSetting kRgba8Range{
    "gi.rgba8_range", 12.0, 0.001, 10000.0,
    "Largest SH coefficient an rgba8 volume stores, over its cells' "
    "cross-section (m^2): too small clips light, too large rounds dim light"};
const engine::BoolSetting kDamping{"gi.damping", true,
                                   "Anisotropic damping of light arriving through surfaces"};
const engine::BoolSetting kOcclusion{
    "gi.occlusion", true,
    "Geometry volume from the RSM and camera depth attenuates propagation (stops leaks through walls)"};
// On by default since the light's coverage is closed over one-cell holes (gv_faces_body.glsl):
// before, where the light's surfels left a wall's faces partly open (a wall the sun grazes), the
// lookup read through some cells and not others, and the Cornell box's back wall showed cell-sized
// blotches. The console preset turns it off: its face volumes would take the plan past 3 MiB.
const engine::BoolSetting kLookupOcclusion{
    "gi.lookup_occlusion", true,
    "With gi.occlusion, the coarse cascades' lookups also keep to the faces their geometry volumes leave "
    "open (the finest cascade's always does), so light beyond a wall thinner than a cell is not read "
    "through it; a face volume per cascade (4 bytes a cell)"};
// Off, the cascades share one injection volume and partial sums and propagate one after another,
// each finer one taking the coarser one's light of this frame: the chain of dependent GPU passes
// grows by the iterations with every cascade (issue 46).
const engine::BoolSetting kCascadesTogether{
    "gi.cascades_together", true,
    "All cascades propagate in the same dependent steps, each with its own injection volume and partial "
    "sums (with float volumes, gi.lookup_occlusion and gi.bounce_cascades=1; otherwise one after another); "
    "a finer cascade takes the light from beyond its border from the coarser one's previous frame"};
// Only the finest cascade took the camera until each sample added its area: marking a coarse cell
// whole made every small object block it, and whether a sample landed in it changed with every
// camera move. Without it the coarse cascades block only what the light sees, and the light of a
// wall's sunlit outside reached a room through the walls the sun does not light (the Cornell box,
// sealed, seen from inside: 9.7% of the open box's light, 3.6% with them). The console preset turns it off.
const engine::BoolSetting kCoarseCameraOcclusion{
    "gi.coarse_camera_occlusion", true,
    "With gi.occlusion, the coarse cascades' geometry volumes also take the camera's depth buffer (the "
    "area of surface each sample stands for), not only the light's surfels (the finest cascade's always "
    "does); 12 bytes a geometry volume cell"};
const engine::BoolSetting kGlossy{
    "gi.glossy", true,
    "Glossy reflections: a few cells marched along the reflected view ray through the LPV (by roughness)"};
const engine::FloatSetting kGlossyMaxRoughness{
    "gi.glossy_max_roughness", 1.0, 0.0, 1.0,
    "Surfaces this rough or rougher get no glossy march (it fades out over the 0.1 below) and reflect the "
    "volume at their lobe's mean direction instead, saving the march's cost per pixel; 1: all but the fully "
    "rough ones"};
// The propagation scatters its first bounce within a few cells of the lit surfaces and leaves
// the far side of a room dark (docs/gi-fidelity.md); gathered per pixel, the first bounce lands
// where a path tracer puts it.
const engine::EnumSetting<LpvSettings::Gather> kGather{
    "gi.gather",
    LpvSettings::Gather::Auto,
    {{LpvSettings::Gather::Auto, "auto"}, {LpvSettings::Gather::On, "on"}, {LpvSettings::Gather::Off, "off"}},
    "The first bounce in the three finest cascades (all of the default three) gathered per pixel from their "
    "VPLs (interleaved over 4 x 4 pixels) instead of read from the propagated volume, which keeps the "
    "further "
    "bounces, glossy and fog; with gi.occlusion a VPL does not light what the scene's surfaces hide from it; "
    "with "
    "gi.bounces > 1 the second bounce too, reflected off the geometry volume's faces from the gathered "
    "first. auto: on a GPU, off on a CPU rasterizer (lavapipe, llvmpipe: seconds a frame) and on the "
    "console profiles (their modelled GPUs)"};
const engine::IntSetting kBounces{
    "gi.bounces", 1, 1, 3,
    "Light bounces: 2-3 reflect the light the geometry volume blocks off its surfels (needs gi.occlusion)"};
const engine::IntSetting kBounceCascades{
    "gi.bounce_cascades", 1, 1, 4,
    "Cascades, finest first, that add the further bounces of gi.bounces (more than gi.cascades: every "
    "cascade); the coarser ones carry one bounce (each costs about a propagation)"};
const engine::IntSetting kLightRsms{"gi.light_rsms", 1, 0, 4,
                                    "Spot lights (the brightest reaching the volume) with their own RSM: "
                                    "bounce light in the colour they hit"};
const engine::IntSetting kPointLightRsms{
    "gi.point_light_rsms", 1, 0, 2,
    "Point lights (the brightest reaching the volume) with a cube RSM of their own, six gi.rsm_size faces: "
    "bounce light in the colour they hit"};
const engine::EnumSetting<uint32_t> kResolution{
    "gi.resolution",
    2u,
    {{1u, "full"}, {2u, "half"}, {4u, "quarter"}},
    "Pixels per axis given a GI lookup and glossy march (full, half, quarter); the lighting pass rebuilds "
    "the others with a depth- and normal-aware (bilateral) filter"};
const engine::IntSetting kDebugSlice{"gi.debug_slice", 16, 0, 63,
                                     "Volume slice (z) shown by gi.debug_view=volume_slice"};

const engine::BoolSetting kAnalyticLights{
    "gi.analytic_lights", true,
    "Point and spot lights lit through the LPV (added analytically, no RSM) instead of per pixel"};
const engine::EnumSetting<GiBudgetPolicy> kBudgetPolicy{
    "gi.budget_policy",
    GiBudgetPolicy::Fixed,
    {{GiBudgetPolicy::Fixed, "fixed"}, {GiBudgetPolicy::Adapt, "adapt"}},
    "GI over the platform budget: fixed only reports it; adapt turns gi.gather off, then updates coarse "
    "cascades less often, then lowers iterations, then the RSM size, then gi.resolution, then gi.bounces"};

// The participating medium (FogSettings, gi/FogMarch.h).
const engine::BoolSetting kFogEnabled{
    "fog.enabled", false,
    "Fog lit by the sun (light shafts through its shadow map) and by the GI's indirect light"};
const engine::FloatSetting kFogDensity{"fog.density", 0.02, 0.0, 10.0,
                                       "Fog extinction per metre at and below fog.base_height"};
const engine::Vec3Setting kFogAlbedo{
    "fog.albedo",
    {0.9f, 0.9f, 0.9f},
    0.0,
    1.0,
    "Fog single-scattering albedo per channel (scattered over extinguished)"};
const engine::FloatSetting kFogHeightFalloff{
    "fog.height_falloff", 0.0, 0.0, 100.0,
    "Exponential height fog: above fog.base_height the density falls by exp(-falloff x metres above); 0: "
    "homogeneous"};
const engine::FloatSetting kFogBaseHeight{"fog.base_height", 0.0, -1.0e6, 1.0e6,
                                          "Height (metres) up to which the fog has fog.density"};
const engine::FloatSetting kFogAnisotropy{
    "fog.anisotropy", 0.2, -0.95, 0.95,
    "Henyey-Greenstein g of the fog's phase function: 0 scatters alike every way, > 0 forward (bright "
    "toward the sun)"};
const engine::EnumSetting<uint32_t> kFogResolution{
    "fog.resolution",
    2u,
    {{1u, "full"}, {2u, "half"}, {4u, "quarter"}},
    "Pixels per axis given a fog march (full, half, quarter); the lighting pass rebuilds the others with a "
    "depth-aware filter. gi.budget_policy=adapt may lower it"};
const engine::IntSetting kFogSteps{"fog.steps", 24, 2, 128,
                                   "Fog march steps per ray. gi.budget_policy=adapt may lower it"};

} // namespace

LpvSettings lpvSettingsFrom(const engine::Config& config) {
    LpvSettings s;
    s.enabled = config.get(kEnabled);
    s.gridSize = uint32_t(config.get(kGridSize));
    s.cascades = uint32_t(config.get(kCascades));
    const std::optional<double> cellSize = config.get(kCellSize);
    s.cellSizeAuto = !cellSize;
    s.cellSize = cellSize ? float(*cellSize) : s.cellSize;
    s.coarseUpdateInterval = uint32_t(config.get(kCoarseUpdateInterval));
    s.iterations = uint32_t(config.get(kIterations));
    s.rsmSize = uint32_t(config.get(kRsmSize));
    s.rsmLodTexels = float(config.get(kRsmLodTexels));
    s.vplCount = uint32_t(config.get(kVplCount));
    s.intensity = float(config.get(kIntensity));
    s.shFormat = config.get(kShFormat);
    s.debugView = config.get(kDebugView);
    // The default slice is no one's choice: shown clamped to a smaller volume, never refused.
    if (config.origin(kDebugSlice.decl()) != "default") s.debugSlice = uint32_t(config.get(kDebugSlice));
    s.rgba8Range = float(config.get(kRgba8Range));
    s.damping = config.get(kDamping);
    s.occlusion = config.get(kOcclusion);
    s.lookupOcclusion = config.get(kLookupOcclusion);
    s.cascadesTogether = config.get(kCascadesTogether);
    s.coarseCameraOcclusion = config.get(kCoarseCameraOcclusion);
    s.glossy = config.get(kGlossy);
    s.glossyMaxRoughness = float(config.get(kGlossyMaxRoughness));
    s.gatherMode = config.get(kGather);
    s.gather = s.gatherMode == LpvSettings::Gather::On; // auto: as LightPropagationVolume decides
    s.bounces = uint32_t(config.get(kBounces));
    s.bounceCascades = uint32_t(config.get(kBounceCascades));
    s.lightRsms = uint32_t(config.get(kLightRsms));
    s.pointLightRsms = uint32_t(config.get(kPointLightRsms));
    s.resolutionDivisor = config.get(kResolution);
    s.budgetPolicy = config.get(kBudgetPolicy);
    s.analyticLights = config.get(kAnalyticLights);
    s.fog.enabled = config.get(kFogEnabled);
    s.fog.density = float(config.get(kFogDensity));
    s.fog.albedo = config.get(kFogAlbedo);
    s.fog.heightFalloff = float(config.get(kFogHeightFalloff));
    s.fog.baseHeight = float(config.get(kFogBaseHeight));
    s.fog.anisotropy = float(config.get(kFogAnisotropy));
    s.fog.resolutionDivisor = config.get(kFogResolution);
    s.fog.steps = uint32_t(config.get(kFogSteps));
    return s;
}

LpvSettings readLpvSettings(const engine::Config& config) {
    LpvSettings s = lpvSettingsFrom(config);
    if (const std::optional<LpvSettingsError> error = validateLpvSettings(s)) {
        const auto origin = [&](std::string_view name) {
            const engine::SettingDecl* decl = engine::SettingRegistry::global().find(name);
            return decl ? config.origin(*decl) : std::string("default");
        };
        std::string message = error->message;
        if (!error->related.empty())
            message += " (" + std::string(error->related) + ": " + origin(error->related) + ")";
        throw engine::ConfigError(origin(error->setting), 0, message);
    }
    return s;
}

} // namespace lpv::gi
