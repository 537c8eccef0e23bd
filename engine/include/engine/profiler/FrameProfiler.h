// The frame profiler: named, nestable CPU and GPU scopes, opened by one line per pass
//
//   auto scope = profiler.scope("gi.propagate", &cmd);   // CPU + GPU
//   profiler.setWork(propagationWork(settings));         // counts for the cost model
//
// GPU times come from the RHI's timestamps, read back from a ring some frames later and never
// waited for; every figure carries its timing source (device timestamps, the CPU-after-finish
// fallback of GL on llvmpipe, or CPU only). Per scope it keeps last/mean/median/p95/max over a
// window of frames, the work counts and their predicted Xbox 360 / PS3 cost, and checks each
// frame against the active platform profile's frame and GI budgets. All storage is allocated when
// the profiler is made or when a scope name is first seen, never in a steady-state frame.
//
// Warm-up frames: a frame that made (or freed) GPU resources, or ran a pass for the first time
// (whose pipelines the driver compiled then: Mesa compiles at first use), is marked
// (FrameRecord::warmUp). The live statistics (scopes(), frameCpuMs(), the budget counters) hold
// every frame; the report (ProfileReport.h) leaves warm-up frames out and says how many.
#pragma once

#include "engine/profiler/CostModel.h"
#include "engine/profiler/SampleWindow.h"
#include "engine/profiler/WorkCounts.h"
#include "platforms/PlatformProfile.h"
#include "rhi/Device.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lpv::engine {

struct ProfilerOptions {
    uint32_t statsWindow = 120;  // frames the statistics cover
    uint32_t traceFrames = 1200; // frames kept for the trace and the chart
    uint32_t maxScopesPerFrame = 48;
    uint32_t maxNotes = 256; // notes kept (the newest), see FrameProfiler::note()
    bool gpuTiming = true;   // false: CPU scopes only, no timestamps written
};

// A scope name as it appears in reports: the path of nested names ("gi/propagate").
struct ScopeInfo {
    std::string name;
    std::string path;
    int32_t parent = -1;
    uint32_t depth = 0;
    SampleWindow cpuMs;
    SampleWindow gpuMs;
    WorkCounts work; // of the last frame that ran it
    uint64_t lastFrame = 0;
    // Commands recorded inside it (nested scopes' included) in the last frame that ran it, every
    // time it ran in that frame added (rhi::CommandCounts: dispatches, draws, barriers, stages).
    rhi::CommandCounts commands;
    uint64_t commandsFrame = 0; // the frame `commands` is of
    // A scope not timed on its own whose GPU work runs inside another scope (setTimedIn()): the
    // report names that scope where it would give a timing source.
    std::string timedIn;
};

struct FrameBudgetCheck {
    uint64_t frame = 0; // the device frame these figures are of
    double frameMs = 0; // GPU frame time when resolved, else CPU
    double giMs = 0;    // sum of the top-level "gi" scopes
    double giPredictedX360Ms = 0, giPredictedPs3Ms = 0;
    // The GI passes' work predicted on the active profile's own throughput (the x360 or ps3
    // figures on those profiles, a custom file's on its own).
    double giPredictedMs = 0;
    // The GI time the budget is held to: giPredictedMs on a profile whose [gi] time is
    // "predicted" (x360, ps3), else the measured giMs.
    double giBudgetedMs = 0;
    bool frameOverBudget = false;
    bool giOverBudget = false;
    bool giPredictedOverBudget = false; // "predicted" profiles: giPredictedMs against the GI budget
};

// Why a frame is not steady state (FrameRecord::warmUp, a mask).
enum WarmUpReason : uint8_t {
    // The device's live resources (their number or bytes) changed since the previous frame ended,
    // in the frame or before it (a GI rebuild runs before beginFrame()).
    kWarmUpMadeResources = 1,
    // A scope not seen before opened: the pass ran for the first time.
    kWarmUpFirstRunOfPass = 2,
};

// Warm-up frames so far, by reason (a frame may have both), and how many of them were checked
// against the budgets and found over.
struct WarmUpCounts {
    uint64_t frames = 0, madeResources = 0, firstRunOfPass = 0;
    uint64_t checked = 0, overBudget = 0, overGiBudget = 0;
};

class FrameProfiler {
public:
    FrameProfiler(rhi::Device& device, platforms::PlatformProfile profile, ProfilerOptions options = {});
    ~FrameProfiler();
    FrameProfiler(const FrameProfiler&) = delete;
    FrameProfiler& operator=(const FrameProfiler&) = delete;

    // Call right after Device::beginFrame() and right before Device::endFrame().
    void beginFrame(rhi::CommandList& cmd);
    void endFrame(rhi::CommandList& cmd);
    // Before a report: lets the GPU results of every frame recorded so far arrive (they come
    // framesInFlight frames late) by running that many empty device frames, which are not
    // recorded: they would add near-zero frames to the statistics and the report.
    void collectPending();

    class Scope {
    public:
        Scope(Scope&& other) noexcept : profiler_(other.profiler_) { other.profiler_ = nullptr; }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;
        Scope& operator=(Scope&&) = delete;
        ~Scope() {
            if (profiler_) profiler_->closeScope();
        }

    private:
        friend class FrameProfiler;
        explicit Scope(FrameProfiler* p) : profiler_(p) {}
        FrameProfiler* profiler_;
    };

    // Opens a scope; with a command list it is timed on the GPU too. Closed when the Scope dies.
    [[nodiscard]] Scope scope(std::string_view name, rhi::CommandList* gpu = nullptr);
    // Work counts of the innermost open scope in this frame (replaces earlier counts of this frame).
    void setWork(const WorkCounts& work);
    // The innermost open scope's GPU work is recorded inside scope `path` (such as gi.rebuild, run
    // by render.lighting's pass), so its time is measured there, not in a row of its own.
    void setTimedIn(std::string_view path);
    // A short line about this frame for the report, such as what a scheduler changed and why
    // (topic "GI budget changes"). Between endFrame() and beginFrame() it goes to the next frame.
    // Copied into fixed-size storage: long texts are cut, the oldest notes give way.
    void note(std::string_view topic, std::string_view text);
    // A note about frame `frame`, which has ended (what its GPU work left, read back frames later,
    // or once the device is idle at the end of a run): the report shows it under that frame.
    void note(std::string_view topic, std::string_view text, uint64_t frame);

    const std::vector<ScopeInfo>& scopes() const { return scopes_; }
    // Indices into scopes(), depth first: each scope's children right after it, in the order they
    // were first opened (how the reports list passes, whatever order a frame ran them in).
    std::vector<size_t> scopesInTreeOrder() const;
    // A scope's work counts plus those of every scope nested in it (a parent such as "gi" sets
    // none of its own).
    WorkCounts inclusiveWork(size_t scope) const;
    // A scope's predicted console times: the passes under it (itself included) in the last frame
    // that ran it, each predicted and added, as the budget check adds a frame's GI passes (passes
    // run one after another, each as long as its own busiest unit); the bottleneck is the largest
    // pass's. So a parent counts only what ran in that frame: not a coarse cascade kept from an
    // earlier one, nor a pass that has stopped running. When that frame is no longer recorded (or
    // ran out of sample slots before the scope), the scope's inclusive work predicted as one.
    struct ScopePrediction {
        CostPrediction x360, ps3;
        CostPrediction active; // on the active profile's throughput
    };
    ScopePrediction predicted(size_t scope) const;
    const platforms::PlatformProfile& profile() const { return profile_; }
    const platforms::PlatformProfile& x360() const { return x360_; }
    const platforms::PlatformProfile& ps3() const { return ps3_; }
    rhi::TimestampSource gpuTimingSource() const { return timingSource_; }
    const rhi::AllocationRecord& allocations() const { return device_.allocations(); }
    SampleStats frameCpuMs() const { return frameCpu_.stats(); }
    SampleStats frameGpuMs() const { return frameGpu_.stats(); }
    // Budget check of the newest frame whose GPU results are in (or CPU-only frames).
    const FrameBudgetCheck& lastBudgetCheck() const { return lastCheck_; }
    uint64_t framesOverBudget() const { return framesOverBudget_; }
    // Of those, the frames over the GI time budget (the time the profile holds GI to).
    uint64_t framesOverGiBudget() const { return framesOverGiBudget_; }
    uint64_t framesChecked() const { return framesChecked_; }
    uint64_t gpuResultsLost() const { return gpuLost_; }
    const WarmUpCounts& warmUp() const { return warmUp_; }
    uint32_t openScopes() const { return uint32_t(stack_.size()); }

    // One recorded frame, for the trace and the chart.
    struct Sample {
        uint16_t scope = 0;
        uint64_t cpuBegin = 0, cpuEnd = 0;
        uint64_t gpuBegin = 0, gpuEnd = 0; // 0 when not timed or not resolved
        bool gpuTimed = false;
        WorkCounts work;
        rhi::CommandCounts commands; // recorded between its open and close, nested scopes' included
    };
    struct FrameRecord {
        uint64_t frame = 0;
        uint64_t cpuBegin = 0, cpuEnd = 0;
        uint64_t gpuBegin = 0, gpuEnd = 0;
        bool gpuResolved = false;
        bool checked = false; // budget check done (GPU results in, lost, or CPU-only)
        uint8_t warmUp = 0;   // WarmUpReason bits; 0: a steady-state frame
        uint32_t sampleCount = 0;
        std::vector<Sample> samples;            // capacity maxScopesPerFrame, sized at construction
        uint64_t memoryTotal = 0, memoryGi = 0; // held at endFrame()
        // Commands the frame recorded from Device::beginFrame() to the profiler's endFrame().
        rhi::CommandCounts commands;
        FrameBudgetCheck check;
    };
    struct Note {
        static constexpr size_t kTopicBytes = 32, kTextBytes = 256;
        uint64_t frame = 0;
        uint64_t cpuTime = 0; // when it was noted (the frame's start for notes made before it)
        std::array<char, kTopicBytes> topicBuffer{};
        std::array<char, kTextBytes> textBuffer{};
        std::string_view topic() const { return topicBuffer.data(); }
        std::string_view text() const { return textBuffer.data(); }
    };
    // Notes kept, oldest first; notesDropped() older ones gave way.
    template <typename F> void forEachNote(F&& f) const {
        // Pending notes sit in the ring too, so they take slots from the finished ones.
        const uint64_t n = std::min<uint64_t>(noted_ - pendingNotes_, notes_.size() - pendingNotes_);
        for (uint64_t i = noted_ - pendingNotes_ - n; i < noted_ - pendingNotes_; ++i)
            f(notes_[i % notes_.size()]);
    }
    uint64_t notesDropped() const {
        const uint64_t done = noted_ - pendingNotes_, kept = notes_.size() - pendingNotes_;
        return (done > kept ? done - kept : 0) + pendingLost_;
    }

    // Calls f(scope, cpuMs, gpuMs) once for each scope frame `r` recorded, with the times of all its
    // samples added: a scope a frame enters more than once (a cascade's, whose passes run phase by
    // phase with the other cascades') is one sample of its frame. gpuMs is negative where none
    // of its samples was timed on the GPU (or the frame's results are not in).
    template <typename F> static void forEachScopeIn(const FrameRecord& r, F&& f) {
        const auto ms = [](uint64_t begin, uint64_t end) {
            return end > begin ? double(end - begin) / 1e6 : 0.0;
        };
        for (uint32_t k = 0; k < r.sampleCount; ++k) {
            const uint16_t scope = r.samples[k].scope;
            bool seen = false;
            for (uint32_t j = 0; j < k && !seen; ++j)
                seen = r.samples[j].scope == scope;
            if (seen) continue;
            double cpu = 0.0, gpu = -1.0;
            for (uint32_t j = k; j < r.sampleCount; ++j) {
                const Sample& s = r.samples[j];
                if (s.scope != scope) continue;
                if (s.cpuEnd) cpu += ms(s.cpuBegin, s.cpuEnd);
                if (r.gpuResolved && s.gpuTimed && s.gpuEnd >= s.gpuBegin)
                    gpu = std::max(gpu, 0.0) + ms(s.gpuBegin, s.gpuEnd);
            }
            f(scope, cpu, gpu);
        }
    }

    // Recorded frames, oldest first (up to ProfilerOptions::traceFrames).
    template <typename F> void forEachFrame(F&& f) const {
        const uint64_t n = std::min<uint64_t>(recorded_, records_.size());
        for (uint64_t i = recorded_ - n; i < recorded_; ++i)
            f(records_[i % records_.size()]);
    }

private:
    void closeScope();
    uint16_t internScope(std::string_view name, int32_t parent);
    void resolveGpu();
    void finishCheck(FrameRecord& r);
    // The device's live resources: their number and bytes (allocation-free).
    std::pair<uint64_t, uint64_t> resourceSignature() const;

    rhi::Device& device_;
    platforms::PlatformProfile profile_;
    platforms::PlatformProfile x360_, ps3_;
    ProfilerOptions options_;
    rhi::TimestampSource timingSource_;
    uint32_t gpuSlots_ = 0; // timestamps per frame we may use

    std::vector<ScopeInfo> scopes_;
    std::vector<FrameRecord> records_;
    uint64_t recorded_ = 0; // frames begun
    FrameRecord* current_ = nullptr;
    struct Open {
        uint16_t scope;
        uint32_t sample;
        rhi::CommandList* gpu;
        rhi::CommandCounts commands; // the frame's when it opened
    };
    rhi::CommandList* frameCmd_ = nullptr; // the command list of the frame being recorded
    std::vector<Open> stack_;
    std::vector<uint64_t> timestampScratch_;
    std::vector<Note> notes_;   // ring
    uint64_t noted_ = 0;        // notes ever made
    uint32_t pendingNotes_ = 0; // the newest ones, made before their frame began
    uint64_t pendingLost_ = 0;  // notes that found the ring full of pending ones
    SampleWindow frameCpu_, frameGpu_;
    FrameBudgetCheck lastCheck_;
    uint64_t framesOverBudget_ = 0, framesOverGiBudget_ = 0, framesChecked_ = 0, gpuLost_ = 0;
    std::pair<uint64_t, uint64_t> resources_; // resourceSignature() when the last frame ended
    WarmUpCounts warmUp_;
};

} // namespace lpv::engine
