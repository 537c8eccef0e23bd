// The budget scheduler: the ladder of steps, when to take one and when to give it back, and the
// line the report shows for each.
#include "gi/GiScheduler.h"

#include "engine/profiler/FrameProfiler.h"
#include "gi/LpvSettings.h"
#include "platforms/PlatformProfile.h"

#include <algorithm>
#include <array>
#include <cstdarg>
#include <cstdio>

namespace lpv::gi {
namespace {

// Decimals for a time in a note: 2, or 4 below 0.1 ms (a tiny budget read "0.00 ms").
int digits(double ms) {
    return ms != 0 && ms < 0.1 ? 4 : 2;
}

double mib(uint64_t bytes) {
    return double(bytes) / (1024.0 * 1024.0);
}

__attribute__((format(printf, 2, 3))) void writeText(GiChange& change, const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::vsnprintf(change.textBuffer.data(), change.textBuffer.size(), format, args);
    va_end(args);
}

// A knob's value as its setting takes it: "half" for gi.resolution's lookup every 2 pixels.
struct KnobValue {
    std::array<char, 24> text{};
    KnobValue(GiKnob knob, uint32_t value) {
        if (knob == GiKnob::Gather)
            std::snprintf(text.data(), text.size(), "%s", value != 0 ? "on" : "off");
        else if (knob == GiKnob::Resolution || knob == GiKnob::FogResolution)
            std::snprintf(text.data(), text.size(), "%s",
                          value <= 1   ? "full"
                          : value == 2 ? "half"
                          : value == 4 ? "quarter"
                                       : "?");
        else
            std::snprintf(text.data(), text.size(), "%u", value);
    }
    const char* c_str() const { return text.data(); }
};

// What a knob at a value reads as in the report: the setting that pins it, "gi.rsm_size=128".
struct KnobText {
    std::array<char, 64> text{};
    KnobText(GiKnob knob, uint32_t value) {
        const char* setting = knob == GiKnob::Gather                 ? "gi.gather"
                              : knob == GiKnob::CoarseUpdateInterval ? "gi.coarse_update_interval"
                              : knob == GiKnob::Iterations           ? "gi.iterations"
                              : knob == GiKnob::RsmSize              ? "gi.rsm_size"
                              : knob == GiKnob::Resolution           ? "gi.resolution"
                              : knob == GiKnob::Bounces              ? "gi.bounces"
                              : knob == GiKnob::FogResolution        ? "fog.resolution"
                              : knob == GiKnob::FogSteps             ? "fog.steps"
                                                                     : "";
        if (*setting)
            std::snprintf(text.data(), text.size(), "%s=%s", setting, KnobValue(knob, value).c_str());
    }
    const char* c_str() const { return text.data(); }
};

void setKnob(GiLoad& load, GiKnob knob, uint32_t value) {
    switch (knob) {
    case GiKnob::Gather:
        load.gather = value;
        break;
    case GiKnob::CoarseUpdateInterval:
        load.coarseUpdateInterval = value;
        break;
    case GiKnob::Iterations:
        load.iterations = value;
        break;
    case GiKnob::RsmSize:
        load.rsmSize = value;
        break;
    case GiKnob::Resolution:
        load.resolutionDivisor = value;
        break;
    case GiKnob::Bounces:
        load.bounces = value;
        break;
    case GiKnob::FogResolution:
        load.fogResolutionDivisor = value;
        break;
    case GiKnob::FogSteps:
        load.fogSteps = value;
        break;
    case GiKnob::None:
        break;
    }
}

} // namespace

std::string_view giBudgetPolicyName(GiBudgetPolicy policy) {
    return policy == GiBudgetPolicy::Adapt ? "adapt" : "fixed";
}

GiLoad giLoadOf(const LpvSettings& settings, uint32_t cascades) {
    GiLoad load;
    load.cascades = std::max(cascades, 1u);
    load.coarseUpdateInterval = std::max(settings.coarseUpdateInterval, 1u);
    load.iterations = settings.iterations;
    load.rsmSize = settings.rsmSize;
    load.resolutionDivisor = settings.resolutionDivisor;
    load.bounces = std::max(settings.bounces, 1u);
    load.gather = settings.gather ? 1 : 0;
    load.vplGridSide = std::max(settings.vplGridSide(), 1u);
    if (settings.fog.enabled) {
        load.fogResolutionDivisor = std::max(settings.fog.resolutionDivisor, 1u);
        load.fogSteps = settings.fog.steps;
    }
    return load;
}

void applyGiLoad(const GiLoad& load, LpvSettings& settings) {
    settings.iterations = load.iterations;
    settings.rsmSize = load.rsmSize;
    settings.resolutionDivisor = load.resolutionDivisor;
    settings.bounces = load.bounces;
    settings.gather = load.gather != 0;
    if (load.fogSteps > 0) {
        settings.fog.resolutionDivisor = load.fogResolutionDivisor;
        settings.fog.steps = load.fogSteps;
    }
}

uint32_t cascadeWorkOn(const GiLoad& load, uint32_t cascade, uint64_t frame) {
    if (cascade == 0 || load.cascades <= 1 || load.coarseUpdateInterval <= 1) return kCascadeUpdate;
    const uint64_t k = load.coarseUpdateInterval, coarse = load.cascades - 1, i = cascade - 1;
    if (k >= 2 * coarse) {
        // Two slots per coarse cascade, spread evenly over the cycle: light, then volume.
        if (frame % k == (2 * i * k) / (2 * coarse)) return kCascadeLight;
        if (frame % k == ((2 * i + 1) * k) / (2 * coarse)) return kCascadeVolume;
        return 0;
    }
    // Spread the coarse cascades evenly over the k frames of a cycle.
    return frame % k == ((i * k) / coarse) % k ? uint32_t(kCascadeUpdate) : 0u;
}

bool cascadeUpdatedOn(const GiLoad& load, uint32_t cascade, uint64_t frame) {
    return (cascadeWorkOn(load, cascade, frame) & kCascadeVolume) != 0;
}

uint32_t coarseHalvesInBusiestFrame(uint32_t cascades, uint32_t interval) {
    if (cascades <= 1) return 0;
    GiLoad load;
    load.cascades = cascades;
    load.coarseUpdateInterval = std::max(interval, 1u);
    uint32_t busiest = 0;
    for (uint32_t f = 0; f < load.coarseUpdateInterval; ++f) {
        uint32_t n = 0;
        for (uint32_t c = 1; c < cascades; ++c) {
            const uint32_t work = cascadeWorkOn(load, c, f);
            n += ((work & kCascadeLight) ? 1 : 0) + ((work & kCascadeVolume) ? 1 : 0);
        }
        busiest = std::max(busiest, n);
    }
    return busiest;
}

GiBudget giBudgetOf(const platforms::PlatformProfile& profile) {
    return {profile.giBudgetMs, profile.giMemoryBudgetBytes};
}

std::optional<GiFrameCost> giFrameCost(const engine::FrameProfiler& profiler) {
    if (profiler.framesChecked() == 0) return std::nullopt;
    const engine::FrameBudgetCheck& check = profiler.lastBudgetCheck();
    return GiFrameCost{check.frame, check.giBudgetedMs, profiler.allocations().bytesIn("gi")};
}

GiBudgetScheduler::GiBudgetScheduler(GiSchedulerLimits limits) : limits_(limits) {}

const GiSchedule& GiBudgetScheduler::schedule(uint64_t frame, const std::optional<GiFrameCost>& cost,
                                              const GiBudget& budget, const GiLoad& configured,
                                              GiBudgetPolicy policy) {
    result_.changeCount_ = 0;
    result_.frame = frame;
    if (!started_ || !(configured == configured_) || policy != policy_) {
        start(frame, configured, policy);
    } else if (cost && cost->frame >= loadSince_ && (!lastMeasured_ || cost->frame > *lastMeasured_)) {
        lastMeasured_ = cost->frame;
        // A cycle is judged by its worst frame: the one that updates the most coarse cascades.
        if (cycleFrames_ == 0 || cost->ms > cyclePeakMs_) {
            cyclePeakMs_ = cost->ms;
            cyclePeakFrame_ = cost->frame;
        }
        cyclePeakBytes_ = std::max(cyclePeakBytes_, cost->bytes);
        if (++cycleFrames_ >= cycleLength()) {
            const double ms = cyclePeakMs_;
            const uint64_t bytes = cyclePeakBytes_;
            judgedFrame_ = cyclePeakFrame_;
            cyclePeakMs_ = 0;
            cyclePeakBytes_ = 0;
            cycleFrames_ = 0;
            judge(frame, ms, bytes, budget);
        }
    }
    result_.load = load_;
    result_.policy = policy_;
    result_.stepsInEffect = stepCount_;
    return result_;
}

void GiBudgetScheduler::start(uint64_t frame, const GiLoad& configured, GiBudgetPolicy policy) {
    const bool wasReduced = started_ && stepCount_ > 0;
    started_ = true;
    configured_ = configured;
    policy_ = policy;
    stepCount_ = 0;
    rsmLowersMemory_ = true;
    timeOverReported_ = memoryOverReported_ = floorReported_ = false;
    timeWithinFrames_ = memoryWithinFrames_ = 0;
    result_.timeOverBudget = result_.memoryOverBudget = false;
    setLoad(frame, configured);
    if (wasReduced)
        if (GiChange* c = addChange(GiKnob::None, 0, 0, true))
            writeText(*c,
                      "configured load again (%s, %s, %s, %s, %s): gi settings or gi.budget_policy changed",
                      KnobText(GiKnob::CoarseUpdateInterval, configured.coarseUpdateInterval).c_str(),
                      KnobText(GiKnob::Iterations, configured.iterations).c_str(),
                      KnobText(GiKnob::RsmSize, configured.rsmSize).c_str(),
                      KnobText(GiKnob::Resolution, configured.resolutionDivisor).c_str(),
                      KnobText(GiKnob::Bounces, configured.bounces).c_str());
}

void GiBudgetScheduler::setLoad(uint64_t frame, const GiLoad& load) {
    load_ = load;
    loadSince_ = frame;
    cyclePeakMs_ = 0;
    cyclePeakBytes_ = 0;
    cycleFrames_ = 0;
    overCycles_ = 0;
    calmFrames_ = 0;
}

uint32_t GiBudgetScheduler::cycleLength() const {
    return load_.cascades > 1 ? std::max(load_.coarseUpdateInterval, 1u) : 1u;
}

GiChange* GiBudgetScheduler::addChange(GiKnob knob, uint32_t from, uint32_t to, bool restore) {
    if (result_.changeCount_ == GiSchedule::kMaxChanges) return nullptr;
    GiChange& c = result_.changes_[result_.changeCount_++];
    c.knob = knob;
    c.from = from;
    c.to = to;
    c.restore = restore;
    c.textBuffer[0] = '\0';
    return &c;
}

void GiBudgetScheduler::judge(uint64_t frame, double ms, uint64_t bytes, const GiBudget& budget) {
    const bool timeOver = budget.ms > 0 && ms > budget.ms;
    const bool memoryOver = budget.bytes > 0 && bytes > budget.bytes;
    result_.timeOverBudget = timeOver;
    result_.memoryOverBudget = memoryOver;
    timeWithinFrames_ = timeOver ? 0 : timeWithinFrames_ + cycleLength();
    memoryWithinFrames_ = memoryOver ? 0 : memoryWithinFrames_ + cycleLength();
    if (stepCount_ > 0 && !steps_[stepCount_ - 1].afterKnown) {
        // The first judged cycle after a step says what the step was worth.
        Step& top = steps_[stepCount_ - 1];
        top.msAfter = ms;
        top.bytesAfter = bytes;
        top.afterKnown = true;
        if (top.forMemory && bytes >= top.bytesBefore) rsmLowersMemory_ = false;
    }
    if (policy_ == GiBudgetPolicy::Fixed) {
        reportStates(true, timeOver, memoryOver, ms, bytes, budget);
        return;
    }

    Step step;
    // Only a smaller RSM frees memory; the other knobs save time alone.
    if (memoryOver && rsmLowersMemory_ && rsmStep(step)) {
        step.forMemory = true;
        take(frame, step, ms, bytes, budget);
        return;
    }
    reportStates(false, timeOver, memoryOver, ms, bytes, budget);

    if (timeOver) {
        calmFrames_ = 0;
        if (++overCycles_ < limits_.overBudgetCycles) return;
        overCycles_ = 0;
        if (nextTimeStep(step)) {
            take(frame, step, ms, bytes, budget);
        } else if (!floorReported_) {
            floorReported_ = true;
            // The RSM stops above minRsmSize where the VPL grid's side would no longer divide it.
            KnobText rsm(GiKnob::RsmSize, load_.rsmSize);
            if (load_.rsmSize / 2 >= limits_.minRsmSize)
                std::snprintf(rsm.text.data(), rsm.text.size(), "gi.rsm_size=%u, as gi.vpl_count=%u allows",
                              load_.rsmSize, load_.vplGridSide * load_.vplGridSide);
            if (GiChange* c = addChange(GiKnob::None, 0, 0, false))
                writeText(
                    *c,
                    "frame %llu's GI %.*f ms > %.*f ms budget with every knob at its floor (%s, %s, %s, "
                    "%s, %s)",
                    (unsigned long long)judgedFrame_, digits(ms), ms, digits(budget.ms), budget.ms,
                    KnobText(GiKnob::CoarseUpdateInterval, load_.coarseUpdateInterval).c_str(),
                    KnobText(GiKnob::Iterations, load_.iterations).c_str(), rsm.c_str(),
                    KnobText(GiKnob::Resolution, load_.resolutionDivisor).c_str(),
                    KnobText(GiKnob::Bounces, load_.bounces).c_str());
        }
        return;
    }
    overCycles_ = 0;
    if (timeWithinFrames_ >= limits_.restoreAfterFrames) floorReported_ = false;

    const bool calm = budget.ms <= 0 || ms < limits_.restoreBelow * budget.ms;
    if (!calm || stepCount_ == 0) {
        calmFrames_ = 0;
        return;
    }
    calmFrames_ += cycleLength();
    if (calmFrames_ < limits_.restoreAfterFrames) return;
    // Expect the step back to cost what it saved when it was taken, in proportion.
    const Step& top = steps_[stepCount_ - 1];
    const double expectedMs = top.msAfter > 0 ? ms * top.msBefore / top.msAfter : top.msBefore;
    const uint64_t freed = top.bytesBefore > top.bytesAfter ? top.bytesBefore - top.bytesAfter : 0;
    if (budget.ms > 0 && expectedMs > limits_.restoreFit * budget.ms) return;
    // A step that freed memory comes back only if that memory fits again.
    if (freed > 0 && budget.bytes > 0 && bytes + freed > budget.bytes) return;
    giveBack(frame, ms, expectedMs, budget);
}

// A state is reported when it begins, and its end only once it has lasted restoreAfterFrames, so a
// figure hovering at the budget does not fill the report.
void GiBudgetScheduler::reportStates(bool reportTime, bool timeOver, bool memoryOver, double ms,
                                     uint64_t bytes, const GiBudget& budget) {
    const bool fixed = policy_ == GiBudgetPolicy::Fixed;
    const bool timeEnded = timeOverReported_ && timeWithinFrames_ >= limits_.restoreAfterFrames;
    if (reportTime && ((timeOver && !timeOverReported_) || timeEnded)) {
        timeOverReported_ = timeOver;
        if (GiChange* c = addChange(GiKnob::None, 0, 0, false)) {
            if (timeOver)
                writeText(
                    *c, "frame %llu's GI %.*f ms > %.*f ms budget (gi.budget_policy=fixed: nothing changed)",
                    (unsigned long long)judgedFrame_, digits(ms), ms, digits(budget.ms), budget.ms);
            else
                writeText(*c, "GI within the %.*f ms budget for %u frames (frame %llu's %.*f ms)",
                          digits(budget.ms), budget.ms, timeWithinFrames_, (unsigned long long)judgedFrame_,
                          digits(ms), ms);
        }
    }
    const bool memoryEnded = memoryOverReported_ && memoryWithinFrames_ >= limits_.restoreAfterFrames;
    if ((memoryOver && !memoryOverReported_) || memoryEnded) {
        memoryOverReported_ = memoryOver;
        if (GiChange* c = addChange(GiKnob::None, 0, 0, false)) {
            if (!memoryOver)
                writeText(*c, "GI memory %.2f MiB within the %.2f MiB budget for %u frames", mib(bytes),
                          mib(budget.bytes), memoryWithinFrames_);
            else if (fixed)
                writeText(*c,
                          "GI memory %.2f MiB > %.2f MiB budget (gi.budget_policy=fixed: nothing changed)",
                          mib(bytes), mib(budget.bytes));
            else
                writeText(*c,
                          "GI memory %.2f MiB > %.2f MiB budget and no time knob frees more (lower "
                          "gi.cascades, gi.grid_size or gi.sh_format)",
                          mib(bytes), mib(budget.bytes));
        }
    }
}

bool GiBudgetScheduler::nextTimeStep(Step& step) const {
    if (gatherStep(step)) return true;
    if (load_.cascades > 1) {
        // A longer interval only helps when the busiest frame then runs less coarse work: with
        // three coarse cascades, every 4 frames has the same worst frame as every 2.
        // Doubling, capped at the limit (a configured interval of 3 can still go to 4).
        const uint32_t now = coarseHalvesInBusiestFrame(load_.cascades, load_.coarseUpdateInterval);
        for (uint32_t k = std::max(load_.coarseUpdateInterval, 1u); k < limits_.maxCoarseUpdateInterval;) {
            k = std::min(k * 2, limits_.maxCoarseUpdateInterval);
            if (coarseHalvesInBusiestFrame(load_.cascades, k) < now) {
                step = {GiKnob::CoarseUpdateInterval, load_.coarseUpdateInterval, k};
                return true;
            }
        }
    }
    if (load_.iterations > limits_.minIterations) {
        // A quarter at a time (at least one): long settings converge in a few steps, short ones
        // lose one iteration per step.
        const uint32_t to =
            std::max(limits_.minIterations, load_.iterations - std::max(1u, load_.iterations / 4));
        step = {GiKnob::Iterations, load_.iterations, to};
        return true;
    }
    return rsmStep(step) || resolutionStep(step) || bouncesStep(step) || fogStep(step);
}

bool GiBudgetScheduler::gatherStep(Step& step) const {
    // First: the per-pixel gather costs most where the budget is a console's (about 236 ms at
    // 1280x720 on the Xbox 360's model, lpv_bench --parts=console), and without it the volume
    // still carries the first bounce.
    if (load_.gather == 0) return false;
    step = {GiKnob::Gather, 1, 0};
    return true;
}

bool GiBudgetScheduler::fogStep(Step& step) const {
    // After the GI's own knobs: the fog's cost is its march, first over fewer pixels (the rebuild
    // keeps its edges at depth steps), then in fewer, longer steps (coarser shafts).
    if (load_.fogSteps == 0) return false;
    const uint32_t d = std::max(load_.fogResolutionDivisor, 1u);
    if (d * 2 <= limits_.maxFogResolutionDivisor) {
        step = {GiKnob::FogResolution, d, d * 2};
        return true;
    }
    if (load_.fogSteps / 2 < limits_.minFogSteps) return false;
    step = {GiKnob::FogSteps, load_.fogSteps, load_.fogSteps / 2};
    return true;
}

bool GiBudgetScheduler::bouncesStep(Step& step) const {
    // After the resolution: a further bounce is a whole propagation more in the finest cascades
    // (gi.bounce_cascades), but its light is a fraction of the first's, so it goes last.
    if (load_.bounces <= 1) return false;
    step = {GiKnob::Bounces, load_.bounces, load_.bounces - 1};
    return true;
}

bool GiBudgetScheduler::resolutionStep(Step& step) const {
    // Last: fewer lookups cost the picture detail at silhouettes (engine::IndirectLighting).
    const uint32_t d = std::max(load_.resolutionDivisor, 1u);
    if (d * 2 > limits_.maxResolutionDivisor) return false;
    step = {GiKnob::Resolution, d, d * 2};
    return true;
}

bool GiBudgetScheduler::rsmStep(Step& step) const {
    const uint32_t half = load_.rsmSize / 2;
    if (half < limits_.minRsmSize || half % std::max(load_.vplGridSide, 1u) != 0) return false;
    step = {GiKnob::RsmSize, load_.rsmSize, half};
    return true;
}

void GiBudgetScheduler::take(uint64_t frame, Step step, double ms, uint64_t bytes, const GiBudget& budget) {
    if (stepCount_ == kMaxSteps) return; // the ladder is shorter than the stack
    step.msBefore = ms;
    step.bytesBefore = bytes;
    steps_[stepCount_++] = step;
    GiLoad next = load_;
    setKnob(next, step.knob, step.to);
    setLoad(frame, next);
    if (GiChange* c = addChange(step.knob, step.from, step.to, false)) {
        if (step.forMemory)
            writeText(*c, "%s (was %s): GI memory %.2f MiB > %.2f MiB budget",
                      KnobText(step.knob, step.to).c_str(), KnobValue(step.knob, step.from).c_str(),
                      mib(bytes), mib(budget.bytes));
        else
            writeText(*c, "%s (was %s): frame %llu's GI %.*f ms > %.*f ms budget",
                      KnobText(step.knob, step.to).c_str(), KnobValue(step.knob, step.from).c_str(),
                      (unsigned long long)judgedFrame_, digits(ms), ms, digits(budget.ms), budget.ms);
    }
}

void GiBudgetScheduler::giveBack(uint64_t frame, double ms, double expectedMs, const GiBudget& budget) {
    const Step step = steps_[--stepCount_];
    const uint32_t calmFrames = calmFrames_;
    GiLoad next = load_;
    setKnob(next, step.knob, step.from);
    setLoad(frame, next);
    if (GiChange* c = addChange(step.knob, step.to, step.from, true))
        writeText(*c,
                  "restored %s (was %s): GI under %.0f%% of the %.*f ms budget for %u frames (frame %llu's "
                  "%.*f ms), %.*f ms expected",
                  KnobText(step.knob, step.from).c_str(), KnobValue(step.knob, step.to).c_str(),
                  limits_.restoreBelow * 100.0, digits(budget.ms), budget.ms, calmFrames,
                  (unsigned long long)judgedFrame_, digits(ms), ms, digits(expectedMs), expectedMs);
}

} // namespace lpv::gi
