// The GI budget scheduler: under gi.budget_policy=adapt it keeps GI inside the platform profile's
// time and memory budgets by lowering, one step at a time and always in this order,
//   1. how often the coarse cascades update (every 1 -> 2 -> 4 frames; only with cascades > 1; with
//      a frame or more of its own per coarse cascade, each update is split over two frames),
//   2. the propagation iterations (a quarter, at least one, per step, down to a floor),
//   3. the RSM size (halved per step, down to a floor),
//   4. the pixels looked up (gi.resolution: full -> half -> quarter per axis; the lighting pass
//      rebuilds the rest),
//   5. the bounces (gi.bounces: one fewer per step, down to the first bounce),
//   6. with fog on, the pixels marched through it (fog.resolution, as gi.resolution), then its
//      steps (fog.steps, halved per step down to a floor),
// and gives steps back in reverse order once GI has stayed well under budget for a while and the
// step is expected to fit. Memory over budget is helped only by a smaller RSM; past that it is
// reported, since no time knob frees memory. Under fixed it changes nothing and reports.
//
// It works on a plain struct of knobs and on figures the caller measures (or predicts) per frame,
// so it knows nothing about GPUs or cascades' implementation. Per frame, before recording GI
// (`frame` = device.frameIndex() + 1 before beginFrame(), the index the profiler will record):
//
//   const LpvSettings configured = readLpvSettings(config);   // as configured, never the output
//   const GiSchedule& s = scheduler.schedule(frame, giFrameCost(profiler), giBudgetOf(profile),
//                                            giLoadOf(configured, cascades), configured.budgetPolicy);
//   LpvSettings effective = configured;
//   applyGiLoad(s.load, effective);         // iterations, rsm size
//   ... run the halves s.cascadeWork(c) of cascade c's update ...
//   for (const GiChange& c : s.changes()) profiler.note(kGiBudgetNoteTopic, c.text());
//
// Feed it the configured knobs each frame, not what it returned: a change of the configured load
// starts over from it.
//
// Nothing here allocates after construction: changes are written into fixed-size buffers.
#pragma once

#include "gi/GiBudgetPolicy.h"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace lpv::platforms {
struct PlatformProfile;
}
namespace lpv::engine {
class FrameProfiler;
}

namespace lpv::gi {

struct LpvSettings;

// The profiler topic the scheduler's notes go under (the report's section heading).
inline constexpr std::string_view kGiBudgetNoteTopic = "GI budget changes";

// The knobs the scheduler turns. Cascade 0 is the finest and updates every frame; 1.. are coarse.
struct GiLoad {
    uint32_t cascades = 1;
    uint32_t coarseUpdateInterval = 1; // frames between two updates of a coarse cascade
    uint32_t iterations = 8;
    uint32_t rsmSize = 256;
    uint32_t resolutionDivisor = 1; // per axis: the lookup and glossy march run on 1 in d^2 pixels
    uint32_t bounces = 1;           // gi.bounces: the first is the propagated light itself
    uint32_t gather = 0;            // 1: gi.gather runs (as resolved for the device)
    // fog.resolution and fog.steps; 0 while fog is off (nothing to lower).
    uint32_t fogResolutionDivisor = 0;
    uint32_t fogSteps = 0;
    // Not a knob: the RSM size must stay a multiple of the VPL grid side (gi.vpl_count's rule).
    uint32_t vplGridSide = 1;
    bool operator==(const GiLoad&) const = default;
};

GiLoad giLoadOf(const LpvSettings& settings, uint32_t cascades = 1);
// Writes the knobs LpvSettings holds (iterations, rsm size, resolution, bounces) back into `settings`.
void applyGiLoad(const GiLoad& load, LpvSettings& settings);

// A cascade's update in two halves: its light (the RSM and its VPLs), then its volume (occlusion,
// injection, propagation and bounces, which replace its result).
enum CascadeWork : uint32_t { kCascadeLight = 1u, kCascadeVolume = 2u, kCascadeUpdate = 3u };
// What of `cascade`'s update runs on `frame` (CascadeWork bits; 0: nothing). Coarse cascades take
// turns (staggered phases), so with an interval of k the busiest frame updates ceil(coarse
// cascades / k) of them, not all of them. Once the interval gives every coarse cascade two frames
// of its own (k >= 2 x coarse cascades), its light runs on the first and its volume on the next:
// the busiest frame then runs half of one coarse cascade's update.
uint32_t cascadeWorkOn(const GiLoad& load, uint32_t cascade, uint64_t frame);
// Whether `cascade`'s result is replaced on `frame` (its volume half runs).
bool cascadeUpdatedOn(const GiLoad& load, uint32_t cascade, uint64_t frame);
// The most halves of coarse-cascade updates any one frame runs under that pattern (a whole update
// counts two).
uint32_t coarseHalvesInBusiestFrame(uint32_t cascades, uint32_t interval);

struct GiBudget {
    double ms = 0;      // <= 0: no time budget
    uint64_t bytes = 0; // 0: no memory budget
};
GiBudget giBudgetOf(const platforms::PlatformProfile& profile);

// What one frame of GI cost: time (predicted or measured, the caller's choice) and GI memory.
struct GiFrameCost {
    uint64_t frame = 0; // the frame the figures belong to (GPU times arrive frames late)
    double ms = 0;
    uint64_t bytes = 0;
};
// From the profiler's newest checked frame: the predicted console ms on the x360 and ps3 profiles,
// the measured GI ms otherwise, and the GI bytes allocated now. Empty until a frame is checked.
std::optional<GiFrameCost> giFrameCost(const engine::FrameProfiler& profiler);

enum class GiKnob {
    None,
    Gather,
    CoarseUpdateInterval,
    Iterations,
    RsmSize,
    Resolution,
    Bounces,
    FogResolution,
    FogSteps
};

inline constexpr size_t kGiChangeTextBytes = 256;

// One line of the schedule's report: a knob changed (from -> to) or, with GiKnob::None, a state
// worth saying (over budget under fixed, memory that no knob can lower, nothing left to lower).
struct GiChange {
    GiKnob knob = GiKnob::None;
    uint32_t from = 0, to = 0;
    bool restore = false;
    std::array<char, kGiChangeTextBytes> textBuffer{};
    std::string_view text() const { return textBuffer.data(); }
};

// The scheduler's answer for one frame.
class GiSchedule {
public:
    uint64_t frame = 0;
    GiLoad load; // what to run this frame
    GiBudgetPolicy policy = GiBudgetPolicy::Fixed;
    bool timeOverBudget = false; // as last judged
    bool memoryOverBudget = false;
    uint32_t stepsInEffect = 0; // reductions from the configured load

    std::span<const GiChange> changes() const { return {changes_.data(), changeCount_}; }
    bool updatesCascade(uint32_t cascade) const { return cascadeUpdatedOn(load, cascade, frame); }
    uint32_t cascadeWork(uint32_t cascade) const { return cascadeWorkOn(load, cascade, frame); }

private:
    friend class GiBudgetScheduler;
    static constexpr size_t kMaxChanges = 4;
    std::array<GiChange, kMaxChanges> changes_{};
    uint32_t changeCount_ = 0;
};

struct GiSchedulerLimits {
    uint32_t maxCoarseUpdateInterval = 4;
    uint32_t minIterations = 4;
    uint32_t minRsmSize = 64;
    uint32_t maxResolutionDivisor = 4;    // gi.resolution=quarter
    uint32_t maxFogResolutionDivisor = 4; // fog.resolution=quarter
    uint32_t minFogSteps = 8;
    // A cycle over budget is the worst frame of one coarse update cycle (interval frames). This
    // many such cycles in a row take a step: more than one rides out a single noisy measurement.
    uint32_t overBudgetCycles = 2;
    // Give a step back only after this many frames under restoreBelow x budget ...
    double restoreBelow = 0.8;
    uint32_t restoreAfterFrames = 30;
    // ... and when the step's own cost, as measured when it was taken, should keep GI under
    // restoreFit x budget. Without this a step worth more than 20% would flip back and forth.
    double restoreFit = 0.95;
};

class GiBudgetScheduler {
public:
    explicit GiBudgetScheduler(GiSchedulerLimits limits = {});

    // Call once per frame, before the GI passes of `frame` are recorded; the answer stays valid
    // until the next call. `cost` is the newest
    // figure available (any earlier frame; frames run before the current load took effect and
    // figures already seen are ignored). A change of `configured` or `policy` starts over from
    // the configured load.
    const GiSchedule& schedule(uint64_t frame, const std::optional<GiFrameCost>& cost, const GiBudget& budget,
                               const GiLoad& configured, GiBudgetPolicy policy);

    const GiSchedulerLimits& limits() const { return limits_; }

private:
    struct Step {
        GiKnob knob = GiKnob::None;
        uint32_t from = 0, to = 0;
        double msBefore = 0, msAfter = 0;
        uint64_t bytesBefore = 0, bytesAfter = 0;
        bool afterKnown = false;
        bool forMemory = false;
    };
    // Two interval steps, up to 60 iteration steps (64 -> 4), a few RSM halvings, two resolutions,
    // two bounces, two fog resolutions and four fog step halvings (128 -> 8).
    static constexpr size_t kMaxSteps = 84;

    void start(uint64_t frame, const GiLoad& configured, GiBudgetPolicy policy);
    void judge(uint64_t frame, double ms, uint64_t bytes, const GiBudget& budget);
    void reportStates(bool reportTime, bool timeOver, bool memoryOver, double ms, uint64_t bytes,
                      const GiBudget& budget);
    bool nextTimeStep(Step& step) const;
    bool gatherStep(Step& step) const;
    bool rsmStep(Step& step) const;
    bool resolutionStep(Step& step) const;
    bool bouncesStep(Step& step) const;
    bool fogStep(Step& step) const;
    void take(uint64_t frame, Step step, double ms, uint64_t bytes, const GiBudget& budget);
    void giveBack(uint64_t frame, double ms, double expectedMs, const GiBudget& budget);
    void setLoad(uint64_t frame, const GiLoad& load);
    uint32_t cycleLength() const;
    GiChange* addChange(GiKnob knob, uint32_t from, uint32_t to, bool restore);

    GiSchedulerLimits limits_;
    bool started_ = false;
    GiLoad configured_;
    GiBudgetPolicy policy_ = GiBudgetPolicy::Fixed;
    GiLoad load_;
    uint64_t loadSince_ = 0; // first frame run with load_
    std::optional<uint64_t> lastMeasured_;
    std::array<Step, kMaxSteps> steps_{};
    uint32_t stepCount_ = 0;
    bool rsmLowersMemory_ = true;

    double cyclePeakMs_ = 0;
    uint64_t cyclePeakFrame_ = 0; // the frame cyclePeakMs_ was measured on
    uint64_t judgedFrame_ = 0;    // the judged cycle's peak frame, which the notes name
    uint64_t cyclePeakBytes_ = 0;
    uint32_t cycleFrames_ = 0;
    uint32_t overCycles_ = 0;
    uint32_t calmFrames_ = 0;

    // Lasting states are reported when they begin and end, not every frame.
    bool timeOverReported_ = false, memoryOverReported_ = false, floorReported_ = false;
    uint32_t timeWithinFrames_ = 0, memoryWithinFrames_ = 0; // judged frames in a row within budget

    GiSchedule result_;
};

} // namespace lpv::gi
