// Dynamic diffuse GI with a light propagation volume (Kaplanyan 2009; Kaplanyan & Dachsbacher
// 2010), plugged into the renderer as its IndirectLighting. This is the orchestrator: it owns the
// passes and the cascades, and renderIndirect records the passes in the pipeline's order, each a
// profiler scope under "gi" with its work counts and each a class of its own with a record():
//   lightrsm (SpotLightRsms), then per cascade, coarsest first,
//     the light half:  rsm (ReflectiveShadowMap) -> vpl (VplClustering)
//     the volume half: occlusion (GeometryVolume) -> inject (LpvInjection)
//                      -> propagate (LpvPropagation) -> bounces (MultipleBounces)
//   then lights (PointLightInjection) -> classify (CascadeClasses) -> lookup (IndirectLookup)
//   -> glossy (GlossyReflections); renderMedium marches the fog (FogMarch, "gi.fog") and
//   renderDebugOverlay draws GiDebugViews.
// The volumes the passes record into are LpvVolumes. The volume follows the camera, snapped to
// whole cells and kept inside the scene. Each frame update() takes the settings (a plain struct) and
// the frame's inputs (GiFrameInputs: camera, scene, lights, sun); a change of size or format
// remakes the resources on that frame (not a steady-state frame), after checking the platform
// profile's budget; a change of the RSM size or the bounces keeps the cascades' results. The
// engine's adapter (gi/adapter/) reads the settings from gi.* and the inputs from its renderer.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "engine/render/IndirectLighting.h"
#include "engine/scene/OpenSpace.h"
#include "gi/CascadeClasses.h"
#include "gi/FogMarch.h"
#include "gi/GatheredReflection.h"
#include "gi/GeometryVolume.h"
#include "gi/GiConfigResult.h"
#include "gi/GiDebugViews.h"
#include "gi/GiFrameInputs.h"
#include "gi/GiScheduler.h"
#include "gi/GiWork.h"
#include "gi/GlossyReflections.h"
#include "gi/IndirectLookup.h"
#include "gi/LpvInjection.h"
#include "gi/LpvPropagation.h"
#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "gi/LpvVolumes.h"
#include "gi/MultipleBounces.h"
#include "gi/PointLightInjection.h"
#include "gi/ReflectiveShadowMap.h"
#include "gi/SpotLightRsms.h"
#include "gi/SurfaceVoxels.h"
#include "gi/VplClustering.h"
#include "gi/VplGather.h"
#include "platforms/PlatformProfile.h"

#include <algorithm>
#include <array>
#include <memory>
#include <vector>

namespace lpv::gi {

// Where the volume sits this frame: centred ahead of the camera, snapped to whole cells, and
// pushed inside the scene bounds (centred on the scene on axes where the scene is smaller).
VolumeGrid placeVolume(const LpvSettings& settings, glm::vec3 cameraPosition, glm::vec3 cameraForward,
                       const engine::Bounds& sceneBounds);

class LightPropagationVolume final : public engine::IndirectLighting {
public:
    LightPropagationVolume(rhi::Device& device, platforms::PlatformProfile profile);
    ~LightPropagationVolume() override;

    // The scene's geometry, for gi.cell_size = auto (engine::OpenSpace; made here, at load, not in a
    // frame). Without it, auto sizes the finest cascade to the frame's scene bounds.
    void setScene(const engine::Scene& scene);
    // Prepares the frame, before the device's beginFrame(): takes `settings` when they hold
    // together (validateLpvSettings) and fit the platform profile (checkGiBudget), remakes
    // resources on a change, places the volume. Refused, it returns why and the frame runs the
    // configuration accepted before (acceptedSettings(); GI off before the first), as do later
    // frames until settings that fit come: give it acceptedSettings() back, or it checks the
    // refused ones again every frame. The frame is the device's next (rhi::Device::frameIndex() +
    // 1); `inputs` must stay valid until its renderIndirect().
    // With `profiler` (before its beginFrame), gi.budget_policy runs: the budget scheduler picks
    // this frame's iterations, RSM size and which coarse cascades update, from the profiler's
    // newest GI cost, and notes what it changed and why in the profiler's report.
    [[nodiscard]] GiConfigResult update(const LpvSettings& settings, const GiFrameInputs& inputs,
                                        engine::FrameProfiler* profiler = nullptr);
    // The scheduler's answer for the current frame (the configured load without a profiler).
    const GiSchedule& schedule() const { return schedule_; }
    // At the end of a run, once the device is idle: reports what the last frames' GPU work left to
    // say (RGBA8 clipping, read back framesInFlight frames late while running), so a run of one
    // frame warns as a long one does.
    void collectPending(engine::FrameProfiler* profiler);

    void renderIndirect(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                        const engine::GBufferView& gbuffer, rhi::TextureHandle target,
                        rhi::TextureHandle glossyTarget, engine::FrameProfiler* profiler) override;
    void renderDebugOverlay(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                            rhi::TextureHandle output) override;
    // fog.resolution while fog.enabled (with GI on or off: off, the sun alone lights it), else none.
    uint32_t mediumDivisor() const override {
        return settings_.fog.enabled ? settings_.fog.resolutionDivisor : 0;
    }
    // The fog march (FogMarch) through every cascade with a result, a top-level "gi.fog" scope.
    void renderMedium(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                      const engine::GBufferView& gbuffer, const engine::SunShadowView& sun,
                      rhi::TextureHandle target, engine::FrameProfiler* profiler) override;
    // gi.resolution while GI is on; every pixel (the ambient constant) while it is off.
    uint32_t resolutionDivisor() const override {
        return settings_.enabled ? settings_.resolutionDivisor : 1;
    }
    // With gi.analytic_lights the volume carries the point and spot lights (see PointLightInjection),
    // except the spot and point lights with an RSM of their own (gi.light_rsms, gi.point_light_rsms):
    // those the lighting pass lights per pixel, and the volume carries their bounce.
    bool carriesPunctualLight(uint32_t index) const override {
        return settings_.enabled && made_ && analyticLights_ && !spotRsms_->selected(index);
    }
    // While the volume carries the punctual lights, only those with an RSM are lit per pixel.
    uint32_t perPixelLightLimit(engine::LightType type) const override {
        if (!(settings_.enabled && made_ && analyticLights_))
            return IndirectLighting::perPixelLightLimit(type);
        return type == engine::LightType::Spot ? settings_.lightRsms : settings_.pointLightRsms;
    }

    // This frame's settings: the accepted ones as the budget scheduler and the scene left them.
    const LpvSettings& settings() const { return settings_; }
    // The last settings update() accepted, as given.
    const LpvSettings& acceptedSettings() const { return lastConfigured_; }
    // The finest cascade's placement (cascade(c) for the others).
    const VolumeGrid& grid() const { return grid_; }
    uint32_t cascadeCount() const { return uint32_t(cascades_.size()); }
    const VolumeGrid& cascadeGrid(uint32_t c) const { return cascades_[c].grid; }
    const std::array<rhi::TextureHandle, 3>& cascadeResult(uint32_t c) const { return cascades_[c].result; }
    const LpvVolumes* volumes() const { return volumes_.get(); }
    const ReflectiveShadowMap* rsm() const { return rsm_.get(); }
    const GeometryVolume* geometry() const { return geometry_.get(); }
    // The face transmittance cascade c's lookup keeps to (lpv_lookup.glsl, keptInside), or none
    // where it filters plainly (no gi.occlusion, a coarse cascade without gi.lookup_occlusion, or
    // faces not built yet).
    rhi::TextureHandle lookupFaces(uint32_t c) const {
        const bool kept = geometry_ && c < 32 && (facesValid_ & (1u << c)) != 0;
        return kept ? geometry_->faceTransmittance(std::min(c, geometry_->faceSlots() - 1))
                    : rhi::TextureHandle{};
    }
    const PointLightInjection* pointLights() const { return pointLights_.get(); }
    const SpotLightRsms* spotLightRsms() const { return spotRsms_.get(); }
    rhi::BufferHandle vplBuffer() const { return vpls_; }
    // The finest cascade's VPLs for the pixels' gather (creases split); none without gi.gather.
    rhi::BufferHandle gatherVplBuffer() const { return gatherVpls_[0]; }

private:
    // How the volume passes (GeometryVolume, LpvInjection) draw their points on this device.
    VolumeDraw volumeDraw() const {
        return device_.caps().vertexShaderLayer ? VolumeDraw::Layered : VolumeDraw::PerSlice;
    }
    // renderIndirect's passes (LightPropagationVolume.cpp), each recording one pass of the frame and
    // returning its work counts; FrameRecording holds the frame's command list, profiler, camera,
    // G-buffer and targets.
    struct FrameRecording;
    void recordLightHalf(const FrameRecording& f, uint32_t c); // rsm, vpl
    void recordVolumeHalf(const FrameRecording& f, uint32_t c,
                          bool whole); // occlusion, inject, propagate, bounces
    engine::WorkCounts recordLightRsms(const FrameRecording& f);
    engine::WorkCounts recordRsm(const FrameRecording& f, uint32_t c);
    engine::WorkCounts recordVpls(const FrameRecording& f, uint32_t c);
    engine::WorkCounts recordOcclusion(const FrameRecording& f, uint32_t c);
    // Every cascade whose bit is set in `cascades`, their geometry volumes built together.
    engine::WorkCounts recordOcclusionTogether(const FrameRecording& f, uint32_t cascades);
    // What cascade c's geometry volume is built from (`lights`: room for the point lights' surfels).
    GeometrySources occlusionSources(const FrameRecording& f, uint32_t c,
                                     std::span<PointLightSurfels> lights) const;
    engine::WorkCounts occlusionWorkOf(const FrameRecording& f, const GeometrySources& src) const;
    engine::WorkCounts recordInjection(const FrameRecording& f, uint32_t c);
    engine::WorkCounts recordPropagation(const FrameRecording& f, uint32_t c);
    // Every cascade whose bit is set in `cascades`, propagated together (gi.cascades_together), and
    // with `bounce` the finest cascade's further bounce (recordBounceReflect).
    engine::WorkCounts recordPropagationTogether(const FrameRecording& f, uint32_t cascades, bool bounce);
    engine::WorkCounts recordBounceReflect(const FrameRecording& f);
    // Where cascade c's propagation writes: its result, or the first bounce kept apart.
    const std::array<rhi::TextureHandle, 3>& propagationTarget(uint32_t c) const;
    // The injection volume and partial sums cascade c uses (its own under gi.cascades_together).
    LpvVolumes& volumesOf(uint32_t c) {
        return c > 0 && !cascadeVolumes_.empty() ? *cascadeVolumes_[c - 1] : *volumes_;
    }
    // The sun's RSM cascade c draws (its own under gi.cascades_together).
    ReflectiveShadowMap& rsmOf(uint32_t c) {
        return c > 0 && !cascadeRsms_.empty() ? *cascadeRsms_[c - 1] : *rsm_;
    }
    CascadeHandoff handoffInto(uint32_t c) const;
    engine::WorkCounts recordBounces(const FrameRecording& f, uint32_t c);
    // Into every cascade whose bit is set in `propagated` (made anew this frame).
    engine::WorkCounts recordAnalyticLights(const FrameRecording& f, uint32_t propagated);
    void recordClasses(const FrameRecording& f);
    engine::WorkCounts recordLookup(const FrameRecording& f);
    engine::WorkCounts recordGlossy(const FrameRecording& f);
    // With several cascades on a device that runs both sides of every branch, each texel's cascade
    // class is found first and each class drawn on its own (CascadeClasses.h).
    bool classified() const { return classes_ && cascades_.size() > 1; }
    // update() for one configuration: refused before anything changes, or taken.
    GiConfigResult prepare(const LpvSettings& configured, const GiFrameInputs& inputs,
                           engine::FrameProfiler* profiler);
    void remake(const LpvSettings& settings);
    // The RSM size or the bounces changed (adapt's knobs): only the resources a cascade's update
    // uses on its way are made again; every cascade keeps its result, so the frame after the change
    // does not make them all at once.
    void replaceUpdateResources(const LpvSettings& settings);
    void warnIfAllocatedOverBudget() const;
    // rgba8: says when the volumes clip (Rgba8Clipping), once and again when it gets worse.
    void reportRgba8Clipping(engine::FrameProfiler* profiler);
    void release();

    rhi::Device& device_;
    platforms::PlatformProfile profile_;
    LpvSettings settings_;
    LpvSettings madeWith_; // what the resources were made (or last replaced) for
    bool made_ = false;
    VolumeGrid grid_;
    // Cascade 0 is the finest; each further one has cells twice the size. Scratch (RSM, VPLs,
    // geometry, injection and partial sums) is shared: cascades are built one after another, but
    // for the injection and partial sums under gi.cascades_together (cascadeVolumes_).
    struct Cascade {
        VolumeGrid grid;       // where `result` is being or was computed: what the lookup uses
        VolumeGrid resultGrid; // where `result`'s contents were computed: what the handoff reads
        VolumeGrid placement;  // where the camera wants it now; becomes `lit` when its light updates
        // Cascade 0's and, together, every cascade's: its volumes' accumulated(); else its own.
        std::array<rhi::TextureHandle, 3> result{};
        // Its light half (GiScheduler.h's CascadeWork), kept for the volume half, which may run a
        // frame later: where the RSM was fitted, its VPLs (cascade 0: vpls_), the light then.
        VolumeGrid lit;
        rhi::BufferHandle vpls;
        glm::vec3 lightDirection{0.0f, -1.0f, 0.0f};
        glm::mat4 lightViewProjection{0.0f}; // its RSM's when its VPLs were clustered
        float vplArea = 0.0f;
        glm::vec3 whiteTexelFlux{0.0f};
    };
    std::vector<Cascade> cascades_;
    GiBudgetScheduler scheduler_;
    GiSchedule schedule_;
    uint32_t lightUpdates_ = ~0u;     // bit c: cascade c's light half runs this frame
    uint32_t volumeUpdates_ = ~0u;    // bit c: cascade c's volume half runs this frame
    bool allocationCheckDue_ = false; // warnIfAllocatedOverBudget after the next lookup
    float clippingReported_ = 0.0f;   // the peak last reported (reportRgba8Clipping), 0: none
    uint32_t cascadesValid_ = 0;      // bit c: cascade c's result holds a solution
    uint32_t facesValid_ = 0;         // bit c: the geometry volume holds cascade c's faces (lookup)
    bool deferredBounces_ = false;
    // The finest cascade's first bounce kept apart (MultipleBounces::first()) holds one, computed at
    // firstGrid_.
    bool firstValid_ = false;
    VolumeGrid firstGrid_;
    // update()'s configuration last accepted, and the scheduler as it was before a changed one
    // (put back when the budget check refuses the change).
    LpvSettings lastConfigured_;
    // gi.cell_size = auto: the open space around the camera, and the cell size last chosen from it.
    engine::OpenSpace openSpace_;
    float autoCellSize_ = 0.0f;
    // The finest cascade's cells for gi.cell_size = auto: `room` (the scene's bounds without an
    // open space) spanned by gridSize - 4 of them.
    float autoCellSize(uint32_t gridSize, const engine::Bounds& room);
    GiBudgetScheduler schedulerBefore_;
    GiSchedule scheduleBefore_; // this frame leaves its further bounces to the next (update())
    GiFrameInputs frame_;       // the last update()'s
    bool haveFrame_ = false;
    bool analyticLights_ = true;
    // The passes and resources made for a configuration (remake), in the frame's order.
    std::unique_ptr<SpotLightRsms> spotRsms_;
    std::unique_ptr<ReflectiveShadowMap> rsm_;                      // cascade 0's, or every cascade's
    std::vector<std::unique_ptr<ReflectiveShadowMap>> cascadeRsms_; // gi.cascades_together: 1, 2, ...
    rhi::BufferHandle vpls_;                                        // cascade 0's
    std::unique_ptr<GeometryVolume> geometry_;                      // gi.occlusion
    std::unique_ptr<LpvVolumes> volumes_;                           // cascade 0's, or every cascade's
    std::vector<std::unique_ptr<LpvVolumes>> cascadeVolumes_;       // gi.cascades_together: 1, 2, ...
    std::unique_ptr<LpvInjection> injection_;                       // into volumes_, made with them
    std::unique_ptr<LpvPropagation> propagation_;                   // in volumes_, made with them
    std::unique_ptr<MultipleBounces> bounces_;                      // gi.bounces > 1
    std::unique_ptr<PointLightInjection> pointLights_;
    // gi.gather: the pass, and the first bounce of the gathered cascades kept apart (cascade 0's
    // is MultipleBounces::first() where that exists).
    std::unique_ptr<VplGather> gather_;
    // gi.gather with gi.bounces > 1: the second bounce reflected from the gathered first.
    std::unique_ptr<GatheredReflection> gatheredReflection_;
    std::unique_ptr<GatheredReflection> thirdReflection_; // gi.bounces = 3: from the second's list
    // gi.gather with gi.occlusion: the faces its visibility marches through.
    std::unique_ptr<SurfaceVoxels> surfaceVoxels_;
    std::array<std::array<rhi::TextureHandle, 3>, VplGather::kCascades> firsts_{};
    // The gather's VPLs of the sun in the gathered cascades (VplClustering's `gatherVpls`), and
    // which hold this cascade's (bit c; until then the gather takes the volume's).
    std::array<rhi::BufferHandle, VplGather::kCascades> gatherVpls_{};
    std::array<rhi::BufferHandle, VplGather::kCascades> gatherWindows_{}; // VplWindows' lists of them
    uint32_t gatherVplsValid_ = 0;
    // The VPL sets the gather sums (the sun's of each gathered cascade, then the lights'); how many.
    // `forPixels`: for the pixels' gather (else the second bounce's reflection, which takes the
    // volume's VPLs: the sun's with creases split gave it more light on faces the truth leaves
    // black), the sun's VPLs with creases split where made, and the finest cascade's second
    // bounce's VPLs last.
    using GatherSources = std::array<GatherSource, VplGather::kCascades + SpotLightRsms::kMaxRsms + 2>;
    uint32_t gatherSources(GatherSources& sources, bool forPixels) const;
    // The finest cascade's second bounce is gathered too (its reflection, GatheredReflection).
    bool secondGathered() const;
    // And its third, reflected from the second's listed faces (gi.bounces = 3).
    bool thirdGathered() const;
    // Cascade c's second bounce reflected from its gathered first into `into`'s injection volume.
    engine::WorkCounts recordGatheredReflection(const FrameRecording& f, uint32_t c, LpvVolumes& into);
    engine::WorkCounts recordSurfaceVoxels(const FrameRecording& f, uint32_t c);
    // The faces cascade c's further bounces reflect from (GatheredReflection).
    ReflectingFaces reflectingFaces(uint32_t c) const;
    const std::array<rhi::TextureHandle, 3>& firstBounce(uint32_t c) const;
    bool gathers(LpvSettings::Gather mode);
    void makeGather(const LpvSettings& settings);
    void releaseGather();
    bool gatherAutoReported_ = false;
    void keepFirstBounces(rhi::CommandList& cmd, uint32_t propagated, uint32_t which = ~0u);
    engine::WorkCounts recordGather(const FrameRecording& f);
    // The passes made once, with the LPV; the lookup first, as it refuses a device that binds too
    // few textures for it.
    IndirectLookup lookup_;
    VplClustering vplClustering_;             // the sun's RSM, per cascade
    std::unique_ptr<CascadeClasses> classes_; // CascadeClasses::wanted
    GlossyReflections glossy_;
    FogMarch fog_;
    GiDebugViews debugViews_;
};

} // namespace lpv::gi
