// The GI orchestrator: the configuration and its resources (update), the cascades' schedule, and
// the frame's passes in the pipeline's order (renderIndirect); each pass records in a file of its
// own (LightPropagationVolume.h lists them).
#include "gi/LightPropagationVolume.h"

#include "engine/profiler/FrameProfiler.h"
#include "gi/GiBudget.h"
#include "gi/GiWork.h"
#include "platforms/Log.h"

#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <type_traits>

namespace lpv::gi {
namespace {

// The blend band between a cascade and the next coarser one: a quarter of a cascade's half-extent
// (CryEngine's e_GIBlendRatio 0.25).
constexpr float kBlendBand = 0.25f;

uint64_t pixelsOf(const rhi::TextureDesc& d) {
    return uint64_t(d.width) * d.height;
}

// The volumes with partial sums of their own (GiBudget.cpp counts them): every cascade's and the
// further bounces' with gi.cascades_together, else the one shared set.
uint32_t volumesWithPartialSums(const LpvSettings& s) {
    return s.propagateTogether() ? s.cascades + (s.bounces > 1 ? 1 : 0) : 1;
}

} // namespace

VolumeGrid placeVolume(const LpvSettings& s, glm::vec3 cameraPosition, glm::vec3 cameraForward,
                       const engine::Bounds& bounds) {
    VolumeGrid g;
    g.size = s.gridSize;
    g.cellSize = s.cellSize;
    const float extent = s.cellSize * float(s.gridSize);
    glm::vec3 center = cameraPosition + glm::normalize(cameraForward) * (0.25f * extent);
    if (!bounds.empty()) {
        for (int a = 0; a < 3; ++a) {
            const float lo = bounds.min[a], hi = bounds.max[a];
            if (hi - lo <= extent)
                center[a] = 0.5f * (lo + hi);
            else
                center[a] = std::clamp(center[a], lo + 0.5f * extent, hi - 0.5f * extent);
        }
    }
    // Whole cells: the volume moves in steps of one cell, so a static scene's lighting only
    // changes when the camera crosses a cell.
    g.origin = glm::floor((center - glm::vec3(0.5f * extent)) / s.cellSize + 0.5f) * s.cellSize;
    return g;
}

LightPropagationVolume::LightPropagationVolume(rhi::Device& device, platforms::PlatformProfile profile)
    : device_(device), profile_(std::move(profile)), lookup_(device), vplClustering_(device, "vpl cluster"),
      glossy_(device), fog_(device), debugViews_(device) {
    // Where a shader runs both sides of its branches: one draw per cascade class.
    if (CascadeClasses::wanted(device)) classes_ = std::make_unique<CascadeClasses>(device);
}

LightPropagationVolume::~LightPropagationVolume() {
    release();
}

void LightPropagationVolume::release() {
    device_.waitIdle();
    for (size_t c = 1; c < cascades_.size(); ++c) {
        if (cascadeVolumes_.empty()) // together, each result is its volumes'
            for (rhi::TextureHandle t : cascades_[c].result)
                device_.destroy(t);
        device_.destroy(cascades_[c].vpls);
    }
    cascades_.clear();
    rsm_.reset();
    cascadeRsms_.clear();
    volumes_.reset();
    cascadeVolumes_.clear();
    injection_.reset();
    propagation_.reset();
    bounces_.reset();
    geometry_.reset();
    pointLights_.reset();
    spotRsms_.reset();
    releaseGather();
    if (vpls_) device_.destroy(vpls_);
    vpls_ = {};
    made_ = false;
}

void LightPropagationVolume::remake(const LpvSettings& s) {
    release();
    clippingReported_ = 0.0f;
    madeWith_ = s;
    rsm_ = std::make_unique<ReflectiveShadowMap>(device_, s.rsmSize);
    propagation_ = std::make_unique<LpvPropagation>(device_, s, 0, volumesWithPartialSums(s));
    // Stacked, the propagation keeps every volume's partial sums.
    const bool partialSums = !propagation_->stacked();
    volumes_ = std::make_unique<LpvVolumes>(device_, s, partialSums);
    injection_ = std::make_unique<LpvInjection>(device_, s);
    cascades_.resize(s.cascades);
    if (s.propagateTogether())
        for (uint32_t c = 1; c < s.cascades; ++c) {
            cascadeVolumes_.push_back(std::make_unique<LpvVolumes>(device_, s, partialSums));
            cascadeRsms_.push_back(std::make_unique<ReflectiveShadowMap>(device_, s.rsmSize));
        }
    cascades_[0].result = volumes_->accumulated();
    for (uint32_t c = 1; c < s.cascades; ++c)
        cascades_[c].result = s.propagateTogether()
                                  ? volumesOf(c).accumulated()
                                  : volumes_->createResult("lpv cascade " + std::to_string(c));
    facesValid_ = 0;
    if (s.occlusion)
        geometry_ = std::make_unique<GeometryVolume>(device_, s.gridSize, s.bounces > 1, s.faceVolumes(),
                                                     s.cameraAreas(), s.propagateTogether());
    if (s.bounces > 1)
        bounces_ =
            std::make_unique<MultipleBounces>(device_, s, *volumes_, s.propagateTogether(), partialSums);
    firstValid_ = false;
    pointLights_ = std::make_unique<PointLightInjection>(device_, s);
    spotRsms_ = std::make_unique<SpotLightRsms>(device_, s);
    if (s.gather) makeGather(s);
    vpls_ = device_.createBuffer({uint64_t(s.vplSlots()) * 48, rhi::kBufferStorage | rhi::kBufferTransfer,
                                  rhi::MemoryAccess::GpuOnly, "vpls", "gi.vpl"});
    // A coarse cascade's VPLs wait a frame for its volume half when the scheduler splits its update.
    cascades_[0].vpls = vpls_;
    for (uint32_t c = 1; c < s.cascades; ++c)
        cascades_[c].vpls = device_.createBuffer(
            {uint64_t(s.vplSlots()) * 48, rhi::kBufferStorage | rhi::kBufferTransfer,
             rhi::MemoryAccess::GpuOnly, "vpls, cascade " + std::to_string(c), "gi.vpl"});
    made_ = true;
}

// gi.gather's pass and the first bounces it keeps apart; made with the volumes, or when adapt turns
// the gather back on.
static_assert(SurfaceVoxels::kCascades == VplGather::kCascades, "the gather marches its cascades' faces");
void LightPropagationVolume::makeGather(const LpvSettings& s) {
    lookup_.enableGather();
    gather_ = std::make_unique<VplGather>(device_);
    if (s.bounces > 1)
        gatheredReflection_ = std::make_unique<GatheredReflection>(device_, s.shFormat, s.gridSize);
    if (s.bounces > 2)
        thirdReflection_ = std::make_unique<GatheredReflection>(device_, s.shFormat, s.gridSize, true);
    if (s.occlusion && device_.caps().fragmentStores)
        surfaceVoxels_ = std::make_unique<SurfaceVoxels>(device_, s.gridSize);
    else if (s.occlusion)
        log::warn("gi: gi.gather on " + device_.caps().deviceName +
                  ", which cannot store from fragment shaders: its light goes through walls (no occlusion)");
    for (uint32_t c = 0; c < std::min(s.cascades, VplGather::kCascades); ++c) {
        firsts_[c] = volumes_->createResult("lpv first bounce, cascade " + std::to_string(c));
        gatherVpls_[c] = device_.createBuffer({uint64_t(s.vplSlots()) * 48, rhi::kBufferStorage,
                                               rhi::MemoryAccess::GpuOnly,
                                               "gather vpls, cascade " + std::to_string(c), "gi.vpl"});
        gatherWindows_[c] = device_.createBuffer(
            {VplWindows::bytes(s.vplGridSide()), rhi::kBufferStorage, rhi::MemoryAccess::GpuOnly,
             "gather vpl windows, cascade " + std::to_string(c), "gi.vpl"});
    }
    gatherVplsValid_ = 0;
}

void LightPropagationVolume::releaseGather() {
    gather_.reset();
    gatheredReflection_.reset();
    thirdReflection_.reset();
    surfaceVoxels_.reset();
    for (auto& first : firsts_)
        for (rhi::TextureHandle& t : first) {
            if (t) device_.destroy(t);
            t = {};
        }
    for (auto* buffers : {&gatherVpls_, &gatherWindows_})
        for (rhi::BufferHandle& b : *buffers) {
            if (b) device_.destroy(b);
            b = {};
        }
    gatherVplsValid_ = 0;
}

void LightPropagationVolume::replaceUpdateResources(const LpvSettings& s) {
    // The old resources' destructors wait for the frames in flight that still use them.
    if (s.rsmSize != madeWith_.rsmSize) {
        // The old ones go first, so the device never holds both sizes.
        const size_t cascadeRsms = cascadeRsms_.size();
        rsm_.reset();
        cascadeRsms_.clear();
        spotRsms_.reset();
        rsm_ = std::make_unique<ReflectiveShadowMap>(device_, s.rsmSize);
        for (size_t c = 0; c < cascadeRsms; ++c)
            cascadeRsms_.push_back(std::make_unique<ReflectiveShadowMap>(device_, s.rsmSize));
        spotRsms_ = std::make_unique<SpotLightRsms>(device_, s);
    }
    madeWith_ = s;
    if (s.gather != (gather_ != nullptr)) {
        // adapt's first knob. Turned back on, no cascade has its first bounce kept yet: every one is
        // made again on the next frame.
        releaseGather();
        if (s.gather) {
            makeGather(s);
            cascadesValid_ = 0;
        }
    }
    if ((s.bounces > 1) != (bounces_ != nullptr)) {
        // The geometry volume keeps surfel albedo for the bounces only; it is built anew for every
        // cascade update, and only the faces of each cascade's last update are kept, for the lookup:
        // a cascade has none again until its next update (facesValid_).
        geometry_.reset();
        bounces_.reset();
        facesValid_ = 0;
        if (s.occlusion)
            geometry_ = std::make_unique<GeometryVolume>(device_, s.gridSize, s.bounces > 1, s.faceVolumes(),
                                                         s.cameraAreas(), s.propagateTogether());
        // Stacked, the bounces' volumes take a slab of the propagation's partial sums or give it back.
        if (propagation_->stacked()) {
            propagation_.reset();
            propagation_ = std::make_unique<LpvPropagation>(device_, s, 0, volumesWithPartialSums(s));
        }
        if (s.bounces > 1)
            bounces_ = std::make_unique<MultipleBounces>(device_, s, *volumes_, s.propagateTogether(),
                                                         !propagation_->stacked());
        gatheredReflection_.reset();
        if (gather_ && s.bounces > 1)
            gatheredReflection_ = std::make_unique<GatheredReflection>(device_, s.shFormat, s.gridSize);
        firstValid_ = false;
    }
    if (gather_ && (s.bounces > 2) != (thirdReflection_ != nullptr)) {
        thirdReflection_.reset();
        if (s.bounces > 2)
            thirdReflection_ = std::make_unique<GatheredReflection>(device_, s.shFormat, s.gridSize, true);
    }
}

// The budget check counts the bytes the configuration's resources hold; the device may allocate
// more (lavapipe rounds 3D images up: the README's Xbox 360 example holds 2.98 MiB and gets 3.14
// MiB), which the profiler's report then shows over the GI memory budget: say why, once after each
// remake (after the first lookup, once every GI resource of the frame exists).
void LightPropagationVolume::warnIfAllocatedOverBudget() const {
    const uint64_t planned = giBytes(giResources(settings_)), allocated = device_.allocations().bytesIn("gi");
    if (allocated <= profile_.giMemoryBudgetBytes) return;
    const auto mib = [](uint64_t b) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3f", double(b) / (1024.0 * 1024.0));
        return std::string(text);
    };
    log::warn("gi: the device allocated " + mib(allocated) + " MiB for GI, over platform '" + profile_.name +
              "' GI memory budget of " + mib(profile_.giMemoryBudgetBytes) +
              " MiB, where the configuration's resources hold " + mib(planned) +
              " MiB (the budget check's count)" +
              (allocated > planned ? ": the device allocates more than they hold, such as sizes rounded up"
                                   : std::string()));
}

void LightPropagationVolume::collectPending(engine::FrameProfiler* profiler) {
    Rgba8Clipping* clipping = volumes_ ? volumes_->clipping() : nullptr;
    if (!clipping) return;
    device_.waitIdle();
    // Frame by frame, oldest first, as while running: a frame that clipped is reported even when a
    // later one did not.
    while (clipping->takeInNextFinished())
        reportRgba8Clipping(profiler);
}

void LightPropagationVolume::reportRgba8Clipping(engine::FrameProfiler* profiler) {
    const Rgba8Clipping* clipping = volumes_ ? volumes_->clipping() : nullptr;
    if (!clipping) return;
    const auto& peaks = clipping->peaks();
    const auto worst = std::max_element(peaks.begin(), peaks.end());
    // From kReportedClipping on, once, and again when the light over the range grows by a tenth:
    // a steady scene that clips says so once, not every frame.
    if (*worst < kReportedClipping || *worst <= clippingReported_ * 1.1f) return;
    clippingReported_ = *worst;
    // No heap: a steady frame may report it. The note leaves out the log's prefix and is short
    // enough for FrameProfiler::Note::kTextBytes.
    static constexpr char kPrefix[] = "gi: RGBA8 volumes clip: ";
    char line[sizeof kPrefix + 192];
    char* const text = line + sizeof kPrefix - 1;
    std::snprintf(line, sizeof kPrefix, "%s", kPrefix);
    const int cascade = int(worst - peaks.begin());
    std::snprintf(text, 192,
                  "cascade %d met light %.2fx gi.rgba8_range (%g); above it light is lost: set "
                  "gi.rgba8_range to %g or more (frame %llu)",
                  // The range the volumes were made with (not a later setting, while GI is off, say).
                  cascade, double(*worst), double(madeWith_.rgba8Range),
                  double(rangeToHold(madeWith_.rgba8Range, *worst)),
                  static_cast<unsigned long long>(clipping->peakFrames()[size_t(cascade)]));
    log::warn(line);
    // Under the frame that met it, not the one that read it back.
    if (profiler) profiler->note(kRgba8ClippingNoteTopic, text, clipping->peakFrames()[size_t(cascade)]);
}

void LightPropagationVolume::setScene(const engine::Scene& scene) {
    openSpace_ = engine::OpenSpace(scene);
    autoCellSize_ = 0.0f;
}

float LightPropagationVolume::autoCellSize(uint32_t gridSize, const engine::Bounds& room) {
    const float extent = room.largestSide();
    if (!(extent > 0.0f)) return autoCellSize_ > 0.0f ? autoCellSize_ : 0.25f;
    // gridSize - 4 cells across the room: two cells' margin on either side for the lookup's filter
    // (the cascades are placed over the room, prepare()).
    float cell = std::clamp(extent / float(gridSize - 4), 0.01f, 100.0f);
    // In eighths of an octave, kept until the room changes by more than one: a camera walking
    // through a room does not rescale the volume, and the light with it, every few steps.
    cell = std::exp2(std::round(std::log2(cell) * 8.0f) / 8.0f);
    if (autoCellSize_ > 0.0f && std::abs(std::log2(cell / autoCellSize_)) < 0.126f) return autoCellSize_;
    autoCellSize_ = cell;
    char line[160];
    std::snprintf(line, sizeof line,
                  "gi: gi.cell_size = auto: %.3f m cells, the room around the camera %.1f m across",
                  double(cell), double(extent));
    log::info(line);
    return cell;
}

GiConfigResult LightPropagationVolume::update(const LpvSettings& settings, const GiFrameInputs& inputs,
                                              engine::FrameProfiler* profiler) {
    GiConfigResult result = prepare(settings, inputs, profiler);
    if (result.accepted) return result;
    // Refused: the frame runs the configuration that ran before (none before the first accepted
    // one: GI off), which prepare() took once already, with this frame's inputs.
    if (!prepare(lastConfigured_, inputs, profiler).accepted) {
        // Only when the inputs changed what it needs (the scene's lights, say): no GI this frame
        // rather than one over its budget.
        settings_.enabled = false;
    }
    return result;
}

GiConfigResult LightPropagationVolume::prepare(const LpvSettings& configured, const GiFrameInputs& inputs,
                                               engine::FrameProfiler* profiler) {
    const engine::CameraMatrices& camera = inputs.camera;
    LpvSettings s = configured;
    // A configuration refused below must leave the scheduler as it was: its steps carry over to
    // the configuration kept. Only a changed configuration can be refused, so only then is its
    // state kept (fixed-size: no heap).
    const bool reconfigured = configured != lastConfigured_;
    if (reconfigured) {
        if (std::optional<LpvSettingsError> error = validateLpvSettings(configured))
            return GiConfigResult::refused(std::string(error->setting), std::move(error->message));
        const uint32_t bindings = device_.caps().fragmentTextureBindings;
        if (configured.enabled && configured.gatherMode == LpvSettings::Gather::On &&
            bindings < IndirectLookup::kGatherTextureBindings)
            return GiConfigResult::refused(
                "gi.gather", "gi.gather: the lookup with the gather binds " +
                                 std::to_string(IndirectLookup::kGatherTextureBindings) +
                                 " fragment textures, and this device (" + device_.caps().deviceName +
                                 ") allows " + std::to_string(bindings) + "; set gi.gather = auto or off");
        schedulerBefore_ = scheduler_;
        scheduleBefore_ = schedule_;
    }
    // gi.cell_size = auto sizes the finest cascade to the room the camera stands in, and the
    // cascades are then placed over that room, not ahead of the camera: placed ahead, the room's
    // far wall fell outside the finest cascade, and its surfaces took their first bounce from the
    // next cascade's coarser VPLs (docs/gi-fidelity.md).
    engine::Bounds placementBounds = inputs.sceneBounds;
    if (s.cellSizeAuto) {
        if (!openSpace_.empty()) placementBounds = openSpace_.roomAround(camera.position);
        s.cellSize = autoCellSize(s.gridSize, placementBounds);
    }
    s.gather = gathers(s.gatherMode); // the load the scheduler starts from has it as resolved
    lightUpdates_ = volumeUpdates_ = ~0u;
    if (configured.enabled) {
        // The scheduler always sees the configured load; what it returns is this frame's. Without
        // a profiler it has no cost to judge, but still spaces the coarse cascades' updates as
        // gi.coarse_update_interval says.
        const uint64_t frame = device_.frameIndex() + 1;
        const std::optional<GiFrameCost> cost = profiler ? giFrameCost(*profiler) : std::nullopt;
        schedule_ = scheduler_.schedule(frame, cost, giBudgetOf(profile_), giLoadOf(s, configured.cascades),
                                        configured.budgetPolicy);
        applyGiLoad(schedule_.load, s);
        lightUpdates_ = volumeUpdates_ = 0;
        for (uint32_t c = 0; c < configured.cascades; ++c) {
            const uint32_t halves = schedule_.cascadeWork(c);
            if (halves & kCascadeLight) lightUpdates_ |= 1u << c;
            if (halves & kCascadeVolume) volumeUpdates_ |= 1u << c;
        }
    }
    frame_ = inputs;
    haveFrame_ = true;
    // RSMs for as many spot (point) lights as the scene has, up to gi.light_rsms
    // (gi.point_light_rsms): none for a scene without.
    s.lightRsms = std::min(s.lightRsms, lightCount(inputs.punctualLights, engine::LightType::Spot));
    s.pointLightRsms =
        std::min(s.pointLightRsms, lightCount(inputs.punctualLights, engine::LightType::Point));
    // Against what the resources were made for, not last frame's settings: a change made while GI
    // was off still applies when it comes back on.
    const bool resized = !made_ || s.vplCount != madeWith_.vplCount || !volumes_->matches(s) ||
                         s.occlusion != (geometry_ != nullptr) || s.cascades != madeWith_.cascades ||
                         s.lookupOcclusion != madeWith_.lookupOcclusion ||
                         s.propagateTogether() != madeWith_.propagateTogether() ||
                         s.coarseCameraOcclusion != madeWith_.coarseCameraOcclusion ||
                         s.lightRsms != madeWith_.lightRsms || s.pointLightRsms != madeWith_.pointLightRsms;
    // What adapt turns (gi/GiScheduler.h) needs no cascade made again: the results stay (a kept
    // cascade shows its old bounce count until its next update), so the frame after a step runs the
    // scheduled cascades only, not every one (on PS3 the PC settings' frame after the RSM step
    // predicted 5.24 ms against 4.59 at most in the cycles around it).
    const bool updateResized =
        !resized && (s.rsmSize != madeWith_.rsmSize || (s.bounces > 1) != (bounces_ != nullptr) ||
                     s.gather != (gather_ != nullptr));
    if (s.enabled && (resized || updateResized)) {
        GiConfigResult fits = checkGiBudget(s, profile_); // before anything else changes
        if (!fits.accepted) {
            if (reconfigured) {
                scheduler_ = schedulerBefore_;
                schedule_ = scheduleBefore_;
            }
            return fits;
        }
        if (resized) {
            remake(s);
            cascadesValid_ = 0;
        } else {
            replaceUpdateResources(s);
        }
        allocationCheckDue_ = true; // after the next lookup (warnIfAllocatedOverBudget)
    }
    // The scheduler's notes once the configuration is accepted.
    if (configured.enabled && profiler)
        for (const GiChange& change : schedule_.changes())
            profiler->note(kGiBudgetNoteTopic, change.text());
    lastConfigured_ = configured;
    settings_ = s;
    // Kept coarse cascades hold the lights as they were added (or not) when they were made: a
    // change makes every cascade again, so none carries the lights twice or misses them.
    const bool analyticLights = s.analyticLights;
    if (analyticLights != analyticLights_) cascadesValid_ = 0;
    analyticLights_ = analyticLights;
    LpvSettings level = s;
    for (Cascade& c : cascades_) {
        c.placement = placeVolume(level, camera.position, camera.forward, placementBounds);
        level.cellSize *= 2.0f;
    }
    grid_ = cascades_.empty() ? placeVolume(s, camera.position, camera.forward, placementBounds)
                              : cascades_[0].placement;
    // Under adapt, a frame that must make cascades its schedule leaves for later (the first frame,
    // or one after the volumes were remade: none has a result yet) does all of them at once; it
    // leaves the finest cascade's further bounces to the next frame, which makes that cascade again
    // anyway (a coarse cascade keeps its result for frames, so it keeps its bounces). A cascade
    // with only one of its halves scheduled still runs both while it has no result.
    // One frame without the second bounce is the least visible way back under the budget: on PS3
    // the console preset's first frame predicted 3.57 ms against 3.12 on every later one.
    deferredBounces_ = false;
    if (s.enabled && s.budgetPolicy == GiBudgetPolicy::Adapt && s.bounces > 1)
        for (uint32_t c = 0; c < uint32_t(cascades_.size()); ++c) {
            const uint32_t bit = 1u << c;
            if (!(cascadesValid_ & bit) && !(lightUpdates_ & volumeUpdates_ & bit)) deferredBounces_ = true;
        }
    if (deferredBounces_ && profiler)
        profiler->note(kGiBudgetNoteTopic, "the finest cascade's further bounces left to the next frame: "
                                           "this frame makes cascades its schedule left for later (they "
                                           "have no result yet)");
    // Before the renderer asks which lights the volume carries.
    if (s.enabled && made_) spotRsms_->select(inputs.punctualLights, cascades_.back().placement);
    return {};
}

// What one renderIndirect records with, and how the report sees each of its passes: a profiler
// scope (its GPU time) under the name the report lists, with the work counts the pass returns for
// the console cost model; without a profiler, neither.
struct LightPropagationVolume::FrameRecording {
    rhi::CommandList& cmd;
    engine::FrameProfiler* profiler;
    const engine::CameraMatrices& camera;
    const engine::GBufferView& gbuffer;
    rhi::TextureHandle target, glossyTarget; // the lookup's, 1/divisor of the G-buffer per axis
    glm::vec3 sunDirection;                  // normalised

    std::optional<engine::FrameProfiler::Scope> scope(const char* name) const {
        return profiler ? std::optional<engine::FrameProfiler::Scope>(profiler->scope(name, &cmd))
                        : std::nullopt;
    }
    // `record` returns the pass's work counts, or nothing for a pass that adds none.
    template <class Record> void pass(const char* name, Record&& record) const {
        const auto s = scope(name);
        if constexpr (std::is_void_v<std::invoke_result_t<Record>>) {
            record();
        } else {
            const engine::WorkCounts work = record();
            if (profiler) profiler->setWork(work);
        }
    }
};

void LightPropagationVolume::renderIndirect(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                                            const engine::GBufferView& gbuffer, rhi::TextureHandle target,
                                            rhi::TextureHandle glossyTarget,
                                            engine::FrameProfiler* profiler) {
    if (!settings_.enabled || !made_ || !haveFrame_ || !frame_.scene) {
        cmd.clearTexture(target, {0, 0, 0, 0}); // GI off: no indirect light at all
        cmd.clearTexture(glossyTarget, {0, 0, 0, 0});
        return;
    }
    const FrameRecording f{
        cmd, profiler, camera, gbuffer, target, glossyTarget, glm::normalize(frame_.sunDirection)};
    const auto giScope = f.scope("gi");
    cmd.beginMarker("gi");
    // The spot and point lights' RSMs follow the lights, not the cascades: drawn once, injected into
    // each cascade they reach.
    if (spotRsms_->rsmCount() > 0) f.pass("lightrsm", [&] { return recordLightRsms(f); });
    // Coarsest first: each finer cascade takes the light from beyond its border from the one
    // around it (CascadeHandoff).
    static const char* const kCascadeScopes[4] = {"cascade0", "cascade1", "cascade2", "cascade3"};
    // A coarse cascade the scheduler skips this frame keeps last frame's result (a cascade that
    // never had one updates regardless); its update may run in two halves on two frames.
    const uint32_t validBefore = cascadesValid_;
    uint32_t propagated = 0; // bit c: cascade c's result is made anew this frame
    for (uint32_t c = 0; c < cascadeCount(); ++c)
        if (!(validBefore & (1u << c)) || (volumeUpdates_ & (1u << c))) propagated |= 1u << c;
    // Together (gi.cascades_together), every cascade's volume half but its injection runs after
    // all of them: the geometry volumes built at once, then the propagations. A finer cascade then
    // reads the coarser one's result of an earlier frame: one that has none yet (the first frame)
    // is made first, the cascades then propagating one after another.
    const bool mode = settings_.propagateTogether();
    bool together = mode;
    for (uint32_t c = 0; c + 1 < cascadeCount(); ++c)
        if ((propagated & (1u << c)) && !(validBefore & (2u << c))) together = false;
    uint32_t lit = 0; // bit c: cascade c's light half runs this frame
    for (uint32_t c = 0; c < cascadeCount(); ++c)
        if (!(validBefore & (1u << c)) || (lightUpdates_ & (1u << c))) lit |= 1u << c;
    cascadesValid_ |= lit | propagated;
    if (mode) {
        // Each cascade has an RSM of its own: every RSM, then every VPL clustering, then every
        // injection, so that each phase of all of them is one stage of the GPU's chain.
        const auto phase = [&](uint32_t cascades, const auto& record) {
            for (uint32_t c = cascadeCount(); c-- > 0;)
                if (cascades & (1u << c)) {
                    const auto cascadeScope = f.scope(kCascadeScopes[c]);
                    record(c);
                }
        };
        phase(lit, [&](uint32_t c) {
            cascades_[c].lit = cascades_[c].placement; // a skipped cascade keeps where it was lit
            f.pass("rsm", [&] { return recordRsm(f, c); });
        });
        phase(lit, [&](uint32_t c) { f.pass("vpl", [&] { return recordVpls(f, c); }); });
        phase(propagated, [&](uint32_t c) { recordVolumeHalf(f, c, false); });
    } else {
        for (uint32_t c = cascadeCount(); c-- > 0;) {
            if (!((lit | propagated) & (1u << c))) continue;
            const auto cascadeScope = f.scope(kCascadeScopes[c]);
            if (lit & (1u << c)) recordLightHalf(f, c);
            if (propagated & (1u << c)) recordVolumeHalf(f, c, true);
        }
    }
    // The finest cascade's further bounces run with it: after its propagation, or (together, one
    // further bounce) from its first bounce of the frame before, propagated with the cascades.
    const bool bounced = (propagated & 1u) && bounces_ && settings_.bouncesIn(0) && !deferredBounces_;
    if (mode && propagated) {
        if (geometry_) f.pass("occlusion", [&] { return recordOcclusionTogether(f, propagated); });
        // One further bounce goes with the cascades, from the finest's first bounce of the frame
        // before where it was placed at the same cell size; otherwise the bounces follow.
        const Cascade& finest = cascades_[0];
        const bool ahead = together && bounced && bounces_->first() && settings_.bounces == 2 &&
                           cascadeCount() < LpvPropagation::kMaxJobs && firstValid_ &&
                           firstGrid_.cellSize == finest.grid.cellSize && firstGrid_.size == finest.grid.size;
        if (ahead) f.pass("bounces", [&] { return recordBounceReflect(f); });
        f.pass("propagate", [&] {
            if (together) return recordPropagationTogether(f, propagated, ahead);
            engine::WorkCounts work;
            for (uint32_t c = cascadeCount(); c-- > 0;)
                if (propagated & (1u << c)) work += recordPropagation(f, c);
            return work;
        });
        // The finest cascade's second bounce, where it is gathered, is kept with its first after it
        // joins the result (recordBounces; below for the bounce that went with the cascades).
        if (gather_) keepFirstBounces(cmd, propagated, bounced && secondGathered() ? ~1u : ~0u);
        if (ahead)
            f.pass("bounces.add", [&] {
                bounces_->recordAdd(f.cmd, *bounces_->ownVolumes(), finest.result, bounces_->first(),
                                    secondGathered() ? &firsts_[0] : nullptr);
            });
        else if (bounced)
            f.pass("bounces", [&] { return recordBounces(f, 0); });
    }
    // With the first bounce kept apart, the finest cascade's result is it plus the further bounces,
    // or (bounces left to the next frame) it alone.
    if ((propagated & 1u) && bounces_ && bounces_->first()) {
        if (!bounced)
            cmd.copyTextures(
                std::array<rhi::TextureCopy, 3>{{{(*bounces_->first())[0], cascades_[0].result[0]},
                                                 {(*bounces_->first())[1], cascades_[0].result[1]},
                                                 {(*bounces_->first())[2], cascades_[0].result[2]}}});
        firstValid_ = true;
        firstGrid_ = cascades_[0].grid;
    }
    if (analyticLights_) f.pass("lights", [&] { return recordAnalyticLights(f, propagated); });
    reportRgba8Clipping(profiler);
    if (classified()) f.pass("classify", [&] { recordClasses(f); });
    if (allocationCheckDue_) {
        allocationCheckDue_ = false;
        warnIfAllocatedOverBudget();
    }
    if (gather_) f.pass("gather", [&] { return recordGather(f); });
    f.pass("lookup", [&] { return recordLookup(f); });
    if (settings_.glossy) f.pass("glossy", [&] { return recordGlossy(f); });
    cmd.endMarker();
}

// A cascade's light half (GiScheduler.h's CascadeWork): the sun's RSM where the cascade is now and
// its VPLs, kept for the volume half.
void LightPropagationVolume::recordLightHalf(const FrameRecording& f, uint32_t c) {
    // A skipped cascade keeps the placement its result was computed at; this one moves now.
    cascades_[c].lit = cascades_[c].placement;
    f.pass("rsm", [&] { return recordRsm(f, c); });
    f.pass("vpl", [&] { return recordVpls(f, c); });
}

// A cascade's volume half, this frame or a later one: its result made anew from the VPLs of its
// light half, where they were lit; with `whole` false only its injection, its geometry volume and
// propagation waiting for the other cascades' (renderIndirect).
void LightPropagationVolume::recordVolumeHalf(const FrameRecording& f, uint32_t c, bool whole) {
    cascades_[c].grid = cascades_[c].lit;
    // The gather's faces where the cascade now is (the gathered ones).
    if (surfaceVoxels_ && c < SurfaceVoxels::kCascades)
        f.pass("voxels", [&] { return recordSurfaceVoxels(f, c); });
    if (whole && geometry_) f.pass("occlusion", [&] { return recordOcclusion(f, c); });
    f.pass("inject", [&] { return recordInjection(f, c); });
    if (!whole) return;
    f.pass("propagate", [&] { return recordPropagation(f, c); });
    const bool bounced = bounces_ && settings_.bouncesIn(c) && !(deferredBounces_ && c == 0);
    if (gather_) keepFirstBounces(f.cmd, 1u << c, bounced && c == 0 && secondGathered() ? ~1u : ~0u);
    if (bounced) f.pass("bounces", [&] { return recordBounces(f, c); });
}

engine::WorkCounts LightPropagationVolume::recordLightRsms(const FrameRecording& f) {
    const uint64_t triangles =
        spotRsms_->record(f.cmd, *frame_.scene, frame_.specularAlbedo, frame_.punctualLights);
    return lightRsmWork(settings_, spotRsms_->rsmCount(), triangles);
}

engine::WorkCounts LightPropagationVolume::recordRsm(const FrameRecording& f, uint32_t c) {
    const Cascade& cascade = cascades_[c];
    ReflectiveShadowMap& rsm = rsmOf(c);
    rsm.fit(cascade.lit, f.sunDirection);
    // Objects smaller than a cell of this cascade are left to the finer ones.
    const uint64_t triangles =
        rsm.record(f.cmd, *frame_.scene, frame_.specularAlbedo, f.sunDirection, frame_.sunRadiance,
                   c == 0 ? 0.0f : cascade.lit.cellSize, settings_.rsmLodTexels);
    return rsmWork(settings_, triangles);
}

engine::WorkCounts LightPropagationVolume::recordVpls(const FrameRecording& f, uint32_t c) {
    Cascade& cascade = cascades_[c];
    const uint32_t side = settings_.vplGridSide();
    const ReflectiveShadowMap& rsm = rsmOf(c);
    const rhi::BufferHandle gatherVpls = c < VplGather::kCascades ? gatherVpls_[c] : rhi::BufferHandle{};
    vplClustering_.record(f.cmd, rsm, side, cascade.vpls, gatherVpls);
    if (gatherVpls) gatherVplsValid_ |= 1u << c;
    // What the volume half needs of the light these VPLs carry.
    const float texelsPerVpl = float(rsm.size() / side) * float(rsm.size() / side);
    cascade.lightDirection = f.sunDirection;
    cascade.lightViewProjection = rsm.lightViewProjection();
    cascade.vplArea = rsm.texelArea() * texelsPerVpl;
    cascade.whiteTexelFlux = frame_.sunRadiance * rsm.texelArea();
    engine::WorkCounts work = vplClusterWork(settings_);
    if (gatherVpls) work += gatherVplWork(settings_);
    return work;
}

GeometrySources LightPropagationVolume::occlusionSources(const FrameRecording& f, uint32_t c,
                                                         std::span<PointLightSurfels> lights) const {
    const Cascade& cascade = cascades_[c];
    GeometrySources src;
    src.vpls = cascade.vpls;
    src.vplCount = settings_.vplSlots();
    src.vplArea = cascade.vplArea;
    src.lightDirection = cascade.lightDirection;
    src.whiteTexelFlux = cascade.whiteTexelFlux;
    // Camera surfels: in the finest cascade a G-buffer sample is small next to a cell and marks it;
    // in a coarse cell one sample of a small or partly seen surface would mark the whole cell, and
    // whether one lands there changes with every camera move, so a coarse cascade's samples add the
    // area they stand for (gi.coarse_camera_occlusion).
    if (c == 0 || settings_.cameraAreas()) {
        src.depth = f.gbuffer.depth;
        src.normal = f.gbuffer.normal;
        src.albedo = f.gbuffer.albedo;
        src.cameraAreas = c > 0;
    }
    src.viewProjection = f.camera.viewProjection;
    src.invViewProjection = f.camera.invViewProjection;
    src.cameraPosition = f.camera.position;
    // The surfels' albedo only where the further bounces read it (gi.bounce_cascades).
    src.surfelAlbedo = settings_.bouncesIn(c);
    // The spot and point lights' RSM surfels that can land in this cascade.
    src.pointLights = lights.first(spotRsms_->surfelsReaching(cascade.grid, lights));
    return src;
}

engine::WorkCounts LightPropagationVolume::occlusionWorkOf(const FrameRecording& f,
                                                           const GeometrySources& src) const {
    uint64_t lightSurfels = 0;
    for (const PointLightSurfels& l : src.pointLights)
        lightSurfels += l.count;
    const uint64_t cameraSamples =
        src.depth ? GeometryVolume::cameraSampleCount(f.gbuffer.width, f.gbuffer.height) : 0;
    engine::WorkCounts work =
        occlusionWork(settings_, src.cameraAreas ? 0 : cameraSamples, volumeDraw(), lightSurfels);
    if (src.cameraAreas) work += cameraAreasWork(settings_, cameraSamples);
    return work;
}

engine::WorkCounts LightPropagationVolume::recordOcclusion(const FrameRecording& f, uint32_t c) {
    std::array<PointLightSurfels, SpotLightRsms::kMaxRsms> lights;
    const GeometrySources src = occlusionSources(f, c, lights);
    // Cascade c's faces go to its own slot, or to the one slot all share (the finest builds last,
    // so the lookup reads its faces there).
    const bool shared = geometry_->faceSlots() == 1;
    geometry_->record(f.cmd, cascades_[c].grid, src, shared ? 0 : c);
    facesValid_ = (shared ? 0u : facesValid_) | (1u << c);
    return occlusionWorkOf(f, src);
}

engine::WorkCounts LightPropagationVolume::recordOcclusionTogether(const FrameRecording& f,
                                                                   uint32_t cascades) {
    std::array<std::array<PointLightSurfels, SpotLightRsms::kMaxRsms>, LpvPropagation::kMaxJobs> lights;
    std::array<GeometrySources, LpvPropagation::kMaxJobs> sources;
    std::array<GeometryVolume::Build, LpvPropagation::kMaxJobs> builds;
    size_t count = 0;
    engine::WorkCounts work;
    // Coarsest first: the finest builds last, so faceTransmittance() is its faces (the bounces').
    for (uint32_t c = cascadeCount(); c-- > 0;) {
        if (!(cascades & (1u << c))) continue;
        sources[count] = occlusionSources(f, c, lights[count]);
        builds[count] = {cascades_[c].grid, &sources[count], c};
        work += occlusionWorkOf(f, sources[count]);
        facesValid_ |= 1u << c;
        ++count;
    }
    geometry_->recordTogether(f.cmd, std::span(builds.data(), count));
    return work;
}

engine::WorkCounts LightPropagationVolume::recordInjection(const FrameRecording& f, uint32_t c) {
    const Cascade& cascade = cascades_[c];
    // The sun's VPLs, then those of the spot and point lights' RSMs that can land in this cascade.
    std::array<VplSource, 1 + SpotLightRsms::kMaxRsms> sources;
    sources[0] = {cascade.vpls, settings_.vplSlots(), glm::vec4(cascade.lightDirection, 0.0f)};
    const uint32_t n = 1 + spotRsms_->sourcesReaching(cascade.grid, std::span(sources).subspan(1));
    injection_->record(f.cmd, volumesOf(c), std::span(sources.data(), n), cascade.grid, settings_.intensity,
                       c);
    return injectWork(settings_, uint64_t(n - 1) * spotLightVplSlots(settings_), volumeDraw());
}

CascadeHandoff LightPropagationVolume::handoffInto(uint32_t c) const {
    return {cascades_[c + 1].result, cascades_[c + 1].resultGrid, cascades_[c].grid};
}

engine::WorkCounts LightPropagationVolume::recordPropagation(const FrameRecording& f, uint32_t c) {
    const bool coarser = c + 1 < cascades_.size();
    CascadeHandoff handoff;
    if (coarser) handoff = handoffInto(c);
    // Its own faces (every cascade's may be built by now), or the one slot all share.
    const rhi::TextureHandle faces =
        geometry_ ? geometry_->faceTransmittance(std::min(c, geometry_->faceSlots() - 1))
                  : rhi::TextureHandle{};
    propagation_->record(f.cmd, volumesOf(c), settings_.iterations, faces, &propagationTarget(c),
                         coarser ? &handoff : nullptr);
    cascades_[c].resultGrid = cascades_[c].grid;
    return propagateWork(settings_);
}

engine::WorkCounts LightPropagationVolume::recordPropagationTogether(const FrameRecording& f,
                                                                     uint32_t cascades, bool bounce) {
    std::array<CascadeHandoff, LpvPropagation::kMaxJobs> handoffs;
    std::array<PropagationJob, LpvPropagation::kMaxJobs> jobs;
    size_t count = 0;
    engine::WorkCounts work;
    // Each handoff reads the coarser cascade's result where it was computed before this frame:
    // the propagations below write the results only at their last step.
    for (uint32_t c = 0; c < cascadeCount(); ++c) {
        if (!(cascades & (1u << c))) continue;
        const bool coarser = c + 1 < cascades_.size();
        if (coarser) handoffs[count] = handoffInto(c);
        jobs[count] = {&volumesOf(c), geometry_ ? geometry_->faceTransmittance(c) : rhi::TextureHandle{},
                       &propagationTarget(c), coarser ? &handoffs[count] : nullptr};
        ++count;
        work += propagateWork(settings_);
    }
    // The finest cascade's further bounce, reflected from its first bounce of the frame before.
    if (bounce) jobs[count++] = bounces_->job(*bounces_->ownVolumes(), *geometry_);
    propagation_->recordTogether(f.cmd, std::span(jobs.data(), count), settings_.iterations);
    for (uint32_t c = 0; c < cascadeCount(); ++c)
        if (cascades & (1u << c)) cascades_[c].resultGrid = cascades_[c].grid;
    return work;
}

engine::WorkCounts LightPropagationVolume::recordBounces(const FrameRecording& f, uint32_t c) {
    // With the gather, a gathered cascade's second bounce is reflected from its gathered first.
    engine::WorkCounts work;
    const bool gathered = c == 0 && secondGathered();
    if (gathered) work += recordGatheredReflection(f, c, volumesOf(c));
    // The third, where gathered too, is reflected from the second's list once that has propagated
    // (the injection volume is free again) and kept with the first two.
    const bool third = gathered && thirdGathered();
    bounces_->record(f.cmd, volumesOf(c), *propagation_, *geometry_, third ? 2 : settings_.bounces,
                     settings_.iterations, cascades_[c].result, c == 0 ? bounces_->first() : nullptr,
                     gathered, gathered ? &firsts_[0] : nullptr);
    if (third) {
        work += thirdReflection_->recordFromList(f.cmd, volumesOf(c), *geometry_, reflectingFaces(c),
                                                 cascades_[c].grid, *gatheredReflection_);
        bounces_->recordFurther(f.cmd, volumesOf(c), *propagation_, *geometry_, settings_.iterations,
                                cascades_[c].result, &firsts_[0]);
    }
    work += bounceWork(settings_);
    return work;
}

engine::WorkCounts LightPropagationVolume::recordGatheredReflection(const FrameRecording& f, uint32_t c,
                                                                    LpvVolumes& into) {
    GatherSources sources;
    const uint32_t count = gatherSources(sources, false);
    return gatheredReflection_->record(f.cmd, into, *geometry_, reflectingFaces(c), cascades_[c].grid, c,
                                       settings_.intensity, std::span(sources.data(), count));
}

ReflectingFaces LightPropagationVolume::reflectingFaces(uint32_t c) const {
    const uint32_t slot = std::min(c, geometry_->faceSlots() - 1);
    ReflectingFaces faces{geometry_->faceTransmittance(slot), (facesValid_ & (1u << slot)) != 0};
    // The surfaces' areas where the cascade's were drawn (recordVolumeHalf) where it is now.
    if (surfaceVoxels_ && c < SurfaceVoxels::kCascades && surfaceVoxels_->stamp(c) != 0) {
        faces.areas = surfaceVoxels_->areas(c);
        faces.areaStamp = surfaceVoxels_->stamp(c);
        faces.areaSamples = SurfaceVoxels::kSamplesPerSide * SurfaceVoxels::kSamplesPerSide;
    }
    return faces;
}

engine::WorkCounts LightPropagationVolume::recordSurfaceVoxels(const FrameRecording& f, uint32_t c) {
    return surfaceVoxelsWork(settings_, surfaceVoxels_->record(f.cmd, *frame_.scene, cascades_[c].grid, c));
}

engine::WorkCounts LightPropagationVolume::recordBounceReflect(const FrameRecording& f) {
    // With the gather, the bounce is reflected from this frame's gathered first bounce.
    if (secondGathered()) {
        engine::WorkCounts work = recordGatheredReflection(f, 0, *bounces_->ownVolumes());
        work += bounceWork(settings_);
        return work;
    }
    // The first bounce was computed where the finest cascade was placed then: its cell c + shift
    // is this frame's cell c.
    const Cascade& finest = cascades_[0];
    const glm::ivec3 shift =
        glm::ivec3(glm::round((finest.grid.origin - firstGrid_.origin) / finest.grid.cellSize));
    bounces_->recordReflect(f.cmd, *bounces_->ownVolumes(), *geometry_, *bounces_->first(), shift);
    return bounceWork(settings_);
}

const std::array<rhi::TextureHandle, 3>& LightPropagationVolume::propagationTarget(uint32_t c) const {
    return c == 0 && bounces_ && bounces_->first() ? *bounces_->first() : cascades_[c].result;
}

engine::WorkCounts LightPropagationVolume::recordAnalyticLights(const FrameRecording& f,
                                                                uint32_t propagated) {
    // Point and spot lights, added already propagated (gi/AnalyticLight.h) to every cascade made
    // this frame, after all propagation so that a coarse cascade made this frame does not hand them
    // on to a finer one (a kept one does, across the finer one's border: +0.1% in the lights hall at
    // gi.coarse_update_interval=2).
    engine::WorkCounts work;
    for (uint32_t c = 0; c < cascades_.size(); ++c) {
        // A cascade kept from an earlier frame holds the lights added then: adding them again
        // counted them twice (the lights hall 12% brighter with gi.coarse_update_interval=2).
        if (!(propagated & (1u << c))) continue;
        const uint32_t n =
            pointLights_->record(f.cmd, frame_.punctualLights, volumesOf(c), cascades_[c].grid,
                                 settings_.intensity, &cascades_[c].result, c, spotRsms_->selection());
        work += analyticLightsWork(settings_, n, pointLights_->cellEvaluations());
    }
    return work;
}

// The work counts feed the console prediction (and adapt's budget): a console's GPU branches per
// texel, so the lookup and the march count that path, here as on a GPU; the classification and the
// class draws' depth tests add nothing to them.
void LightPropagationVolume::recordClasses(const FrameRecording& f) {
    std::array<VolumeGrid, 4> grids;
    for (uint32_t c = 0; c < cascades_.size(); ++c)
        grids[c] = cascades_[c].grid;
    const rhi::TextureDesc& target = device_.desc(f.target);
    classes_->record(f.cmd, f.camera, f.gbuffer, std::span(grids.data(), cascades_.size()), kBlendBand,
                     settings_.glossy ? settings_.glossyMaxRoughness : 0.0f, target.width, target.height,
                     settings_.resolutionDivisor);
}

// gi.gather = auto runs the gather on a GPU that can bind the lookup's inputs. Not on a platform
// whose GI time is predicted for a console's modelled GPU (the Xbox 360's model gives the gather
// about 236 ms at 1280x720, lpv_bench --parts=console), nor on a CPU rasterizer (a CPU-rasterizer
// workaround: every pixel loops over a sixteenth of the VPLs, 6.4 s a 1280x720 frame on
// lavapipe, docs/benchmarks.md); it says so once.
bool LightPropagationVolume::gathers(LpvSettings::Gather mode) {
    if (mode != LpvSettings::Gather::Auto) return mode == LpvSettings::Gather::On;
    const rhi::Caps& caps = device_.caps();
    if (caps.fragmentTextureBindings < IndirectLookup::kGatherTextureBindings || !caps.fragmentStores ||
        profile_.giTimePredicted)
        return false;
    if (caps.concurrentWorkgroups == 0) return true;
    if (!gatherAutoReported_) {
        gatherAutoReported_ = true;
        log::info("gi: gi.gather = auto: off on this CPU rasterizer (" + caps.deviceName +
                  "), where the per-pixel gather costs seconds a frame; gi.gather = on runs it");
    }
    return false;
}

// gi.gather: cascade c's first bounce, where the lookup takes it out (c < VplGather::kCascades); the
// finest's with its second where that is gathered too.
const std::array<rhi::TextureHandle, 3>& LightPropagationVolume::firstBounce(uint32_t c) const {
    return c == 0 && bounces_ && bounces_->first() && !secondGathered() ? *bounces_->first() : firsts_[c];
}

bool LightPropagationVolume::secondGathered() const {
    return gatheredReflection_ && bounces_ && settings_.bouncesIn(0);
}

bool LightPropagationVolume::thirdGathered() const {
    return secondGathered() && thirdReflection_ && settings_.bounces > 2;
}

// Right after propagation, before the further bounces and the analytic lights join the result: the
// part of the light the gather stands for, of the cascades in `propagated` & `which` (the finest
// cascade's with its gathered second bounce is kept as they are summed, MultipleBounces::recordAdd).
void LightPropagationVolume::keepFirstBounces(rhi::CommandList& cmd, uint32_t propagated, uint32_t which) {
    std::array<rhi::TextureCopy, 3 * VplGather::kCascades> copies;
    size_t count = 0;
    for (uint32_t c = 0; c < std::min(cascadeCount(), VplGather::kCascades); ++c) {
        if (!(propagated & which & (1u << c)) || &firstBounce(c) != &firsts_[c]) continue;
        const std::array<rhi::TextureHandle, 3>& source = propagationTarget(c);
        for (uint32_t ch = 0; ch < 3; ++ch)
            copies[count++] = {source[ch], firsts_[c][ch]};
    }
    if (count > 0) cmd.copyTextures(std::span(copies.data(), count)); // one barrier for all
}

uint32_t LightPropagationVolume::gatherSources(GatherSources& sources, bool forPixels) const {
    const uint32_t gathered = std::min(cascadeCount(), VplGather::kCascades);
    // The sun's VPLs of each gathered cascade in its share; the spot and point lights' in the share of
    // every gathered cascade they are injected into (recordInjection).
    uint32_t count = 0;
    // Visibility (gi.occlusion): marched through the surfaces' faces of the cascade whose VPLs
    // they are (SurfaceVoxels); unmarched where they are not drawn (yet).
    const auto facesCascade = [&](uint32_t c) { return std::min(c, SurfaceVoxels::kCascades - 1); };
    const auto stampOf = [&](uint32_t c) {
        return surfaceVoxels_ ? surfaceVoxels_->stamp(facesCascade(c)) : 0u;
    };
    const auto facesOf = [&](uint32_t c) {
        return stampOf(c) != 0 ? surfaceVoxels_->faces(facesCascade(c)) : rhi::TextureHandle{};
    };
    for (uint32_t c = 0; c < gathered; ++c) {
        const float cell = cascades_[c].grid.cellSize;
        const bool split = forPixels && (gatherVplsValid_ & (1u << c)) != 0;
        const rhi::BufferHandle vpls = split ? gatherVpls_[c] : cascades_[c].vpls;
        sources[count++] = {vpls,
                            settings_.vplSlots(),
                            settings_.vplGridSide(),
                            int32_t(c),
                            0,
                            0.25f * cell * cell,
                            facesOf(c),
                            facesCascade(c),
                            stampOf(c),
                            false,
                            {},
                            cascades_[c].lightViewProjection,
                            split ? gatherWindows_[c] : rhi::BufferHandle{}};
    }
    const uint32_t suns = count;
    const float finest = cascades_[0].grid.cellSize;
    // A light's VPLs are marched through the second cascade's faces in every share: a room's lights
    // reach past the finest box (the room) and rarely past the next, whose faces are half the size
    // of the third's.
    const uint32_t lightFaces = std::min(gathered, 2u) - 1;
    for (uint32_t c = 0; c < gathered; ++c) {
        std::array<VplSource, SpotLightRsms::kMaxRsms> reaching;
        const uint32_t n = spotRsms_->sourcesReaching(cascades_[c].grid, reaching);
        for (uint32_t k = 0; k < n; ++k) {
            uint32_t i = suns;
            while (i < count && sources[i].vpls != reaching[k].vpls)
                ++i;
            if (i == count)
                sources[count++] = {reaching[k].vpls,
                                    reaching[k].count,
                                    spotLightVplSide(settings_),
                                    -1,
                                    0,
                                    0.25f * finest * finest,
                                    facesOf(lightFaces),
                                    facesCascade(lightFaces),
                                    stampOf(lightFaces),
                                    false,
                                    {},
                                    reaching[k].viewProjection};
            sources[i].cascades |= 1u << c;
        }
    }
    // The finest cascade's second bounce (GatheredReflection), in its share and in the coarser
    // gathered cascades' where they have no bounces of their own: world-space light, and near the
    // finest cascade's border (a room's walls) the next one answers most of the lookup.
    if (forPixels && secondGathered() && gatheredReflection_->listed()) {
        // Its r^2 grows by a face's area over pi (vpl_gather.frag).
        const float cell = cascades_[0].grid.cellSize;
        uint32_t shares = 1u;
        for (uint32_t c = 1; c < gathered; ++c)
            if (!settings_.bouncesIn(c)) shares |= 1u << c;
        const auto listedBy = [&](const GatheredReflection& r) {
            return GatherSource{
                r.listed(), r.room(),        r.parity(), -1,   shares,       cell * cell / glm::pi<float>(),
                facesOf(0), facesCascade(0), stampOf(0), true, r.faceSlots()};
        };
        sources[count++] = listedBy(*gatheredReflection_);
        // The third (gi.bounces = 3), listed the same way.
        if (thirdGathered() && thirdReflection_->listed()) sources[count++] = listedBy(*thirdReflection_);
    }
    return count;
}

engine::WorkCounts LightPropagationVolume::recordGather(const FrameRecording& f) {
    const rhi::TextureDesc& target = device_.desc(f.target);
    gather_->resize(target.width, target.height); // makes it only when the size changes
    GatherSources sources;
    const uint32_t count = gatherSources(sources, true);
    std::array<VolumeGrid, 4> grids;
    for (uint32_t c = 0; c < cascadeCount(); ++c)
        grids[c] = cascades_[c].grid;
    gather_->record(f.cmd, f.camera, f.gbuffer, std::span(grids.data(), cascadeCount()), kBlendBand,
                    settings_.intensity, settings_.resolutionDivisor, std::span(sources.data(), count));
    uint64_t slots = 0;
    engine::WorkCounts windows;
    for (uint32_t i = 0; i < count; ++i) { // a texel reads one of the second bounce's 16 lists
        slots += sources[i].listed ? GatheredReflection::kPhases * sources[i].slots : sources[i].slots;
        if (sources[i].windows) windows += vplWindowsWork(sources[i].side);
    }
    // A segment crosses a quarter of the grid's faces on average (an estimate; the march stops at
    // the first wall). Every slot counts, lit or not: what the sun's windows leave out of a texel's
    // walk depends on the scene, which the model does not see.
    engine::WorkCounts work =
        gatherWork(pixelsOf(target), slots, count, geometry_ ? settings_.gridSize / 4 : 0);
    work += windows;
    return work;
}

engine::WorkCounts LightPropagationVolume::recordLookup(const FrameRecording& f) {
    std::array<LookupCascade, 4> cascades;
    for (uint32_t c = 0; c < cascades_.size(); ++c) {
        // It keeps to the faces its geometry volume leaves open once they are built (a coarse
        // cascade skipped since the volume was remade has none yet).
        const rhi::TextureHandle faces =
            geometry_ ? geometry_->faceTransmittance(std::min(c, geometry_->faceSlots() - 1))
                      : rhi::TextureHandle{};
        cascades[c] = {cascades_[c].grid, cascades_[c].result, faces,
                       geometry_ && (facesValid_ & (1u << c)) != 0};
    }
    LookupOptions options;
    options.intensity = settings_.intensity;
    options.rgba8Range = volumes_->encoded() ? settings_.rgba8Range : 0.0f;
    options.damping = settings_.damping;
    options.glossyLobe = settings_.glossy;
    options.blendBand = kBlendBand;
    // Each texel looks up the G-buffer pixel at texel x divisor; the lighting pass rebuilds the rest.
    options.divisor = settings_.resolutionDivisor;
    LookupGather gather;
    if (gather_) {
        for (uint32_t c = 0; c < VplGather::kCascades; ++c)
            gather.first[c] = firstBounce(std::min(c, cascadeCount() - 1));
        gather.gathered = gather_->gathered();
    }
    lookup_.record(f.cmd, f.camera, f.gbuffer, std::span(cascades.data(), cascades_.size()), options,
                   f.target, f.glossyTarget, frame_.specularAlbedo, classified() ? classes_.get() : nullptr,
                   gather_ ? &gather : nullptr);
    return lookupWork(settings_, pixelsOf(device_.desc(f.target)));
}

engine::WorkCounts LightPropagationVolume::recordGlossy(const FrameRecording& f) {
    std::array<GlossyCascade, 4> cascades;
    for (size_t c = 0; c < cascades_.size(); ++c)
        cascades[c] = {cascades_[c].grid, cascades_[c].result};
    glossy_.record(f.cmd, f.camera, f.gbuffer, std::span(cascades.data(), cascades_.size()),
                   volumes_->encoded() ? settings_.rgba8Range : 0.0f, settings_.glossyMaxRoughness,
                   f.glossyTarget, frame_.specularAlbedo, settings_.resolutionDivisor,
                   classified() ? classes_.get() : nullptr);
    return glossyWork(pixelsOf(device_.desc(f.target)));
}

void LightPropagationVolume::renderMedium(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                                          const engine::GBufferView& gbuffer,
                                          const engine::SunShadowView& sun, rhi::TextureHandle target,
                                          engine::FrameProfiler* profiler) {
    const auto scope = profiler ? std::optional<engine::FrameProfiler::Scope>(profiler->scope("gi.fog", &cmd))
                                : std::nullopt;
    cmd.beginMarker("fog");
    // The cascades with a result (after renderIndirect this frame, every one of them while GI is on).
    std::array<FogCascade, 4> cascades;
    size_t n = 0;
    if (settings_.enabled && made_ && haveFrame_)
        for (uint32_t c = 0; c < cascadeCount(); ++c)
            if (cascadesValid_ & (1u << c)) cascades[n++] = {cascades_[c].grid, cascades_[c].result};
    // CPU-rasterizer workaround (Caps::maskedBranches): such a device runs every cascade's branch at
    // every step, so there the fog reads the coarsest cascade alone, which holds every other; the
    // fog's indirect light is smooth enough that its coarser cells cost little in the image.
    if (device_.caps().maskedBranches && n > 1) {
        cascades[0] = cascades[n - 1];
        n = 1;
    }
    FogInputs in;
    in.camera = camera;
    in.gbuffer = gbuffer;
    in.sun = sun;
    in.cascades = std::span(cascades.data(), n);
    in.rgba8Range = n > 0 && volumes_->encoded() ? settings_.rgba8Range : 0.0f;
    in.sceneBounds = frame_.sceneBounds;
    fog_.record(cmd, settings_.fog, in, target);
    cmd.endMarker();
    const rhi::TextureDesc& d = device_.desc(target);
    if (profiler) profiler->setWork(fogWork(settings_.fog, uint64_t(d.width) * d.height, n > 0));
}

void LightPropagationVolume::renderDebugOverlay(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                                                rhi::TextureHandle output) {
    if (!settings_.enabled || !made_) return;
    // The sun's VPLs of the finest cascade, then the lights' with an RSM.
    std::array<VplSource, 1 + SpotLightRsms::kMaxRsms> vpls;
    vpls[0] = {vpls_, settings_.vplSlots()};
    const std::span<const VplSource> lights = spotRsms_->sources();
    std::copy(lights.begin(), lights.end(), vpls.begin() + 1);
    debugViews_.record(cmd, settings_.debugView, camera, output, *volumes_, grid_,
                       settings_.debugSlice.value_or(16u), std::span(vpls.data(), 1 + lights.size()));
}

} // namespace lpv::gi
