// Profiler outputs. Built at exit (or on request), so allocation here is fine.
#include "engine/profiler/ProfileReport.h"

#include "engine/profiler/FrameProfiler.h"
#include "platforms/Platform.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace lpv::engine {
namespace {

std::string fixed(double v, int digits = 3) {
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
    return buf;
}

std::string mib(uint64_t bytes) {
    return fixed(double(bytes) / (1024.0 * 1024.0), 3) + " MiB";
}

std::string jsonEscape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;
        out += c;
    }
    return out;
}

std::string xmlEscape(const std::string& s) {
    std::string out;
    for (char c : s)
        out += c == '<'   ? "&lt;"
               : c == '>' ? "&gt;"
               : c == '&' ? "&amp;"
               : c == '"' ? "&quot;"
                          : std::string(1, c);
    return out;
}

std::string gpuSourceName(const FrameProfiler& p) {
    return std::string(rhi::timestampSourceName(p.gpuTimingSource()));
}

struct Row {
    const ScopeInfo* scope;
    SampleStats cpu, gpu;
    CostPrediction x360, ps3, active;
    bool gi;                        // a GI pass: its shares of the GI budget count
    double shareOfFrame, shareOfGi; // percent of the profile's budgets, on the GPU median when timed
    // On a profile whose GI check also holds the predicted time to the GI budget ([gi] time =
    // "predicted": x360, ps3): a GI pass's prediction on that profile's throughput, in percent of
    // the budget; else 0.
    double predictedShareOfGi;
    bool warmUpOnly; // ran in warm-up frames only: its figures are theirs, not held to the budget
};

// A row's timing source: the GPU's, "in <scope>" for work measured inside another scope's time
// (FrameProfiler::setTimedIn), else "cpu" (a scope timed on the CPU only).
std::string timingOf(const FrameProfiler& p, const Row& r) {
    if (r.gpu.count) return gpuSourceName(p);
    return r.scope->timedIn.empty() ? std::string("cpu") : "in " + r.scope->timedIn;
}

// The profile whose predicted time the GI check holds to the budget ("x360", "ps3", a custom
// profile's name), or empty when GI is held to its measured time.
std::string_view predictedProfile(const FrameProfiler& p) {
    return p.profile().giTimePredicted ? std::string_view(p.profile().name) : std::string_view();
}

// The report's statistics are over the steady-state frames still recorded: the warm-up frames
// (FrameRecord::warmUp: they made resources or ran a pass for the first time, compiling its
// pipelines) are left out. When every recorded frame warmed up (a run of one frame) there is no
// steady state, and the statistics are over all of them, said so.
struct SteadyState {
    bool reached = false;
    uint32_t frames = 0;                // frames the statistics cover
    std::vector<uint64_t> warmUpFrames; // recorded warm-up frames
    std::vector<SampleStats> cpu, gpu;  // per scope, over the covered frames
    SampleStats frameCpu, frameGpu;
    bool covers(const FrameProfiler::FrameRecord& r) const { return r.cpuEnd && (!reached || !r.warmUp); }
};

SteadyState steadyState(const FrameProfiler& p) {
    SteadyState st;
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (r.cpuEnd && !r.warmUp) st.reached = true;
        if (r.cpuEnd && r.warmUp) st.warmUpFrames.push_back(r.frame);
    });
    // Windows sized to hold every sample, then filled.
    std::vector<uint32_t> samples(p.scopes().size(), 0);
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (!st.covers(r)) return;
        ++st.frames;
        FrameProfiler::forEachScopeIn(r, [&](uint16_t scope, double, double) { ++samples[scope]; });
    });
    std::vector<SampleWindow> cpu, gpu;
    for (uint32_t n : samples) {
        cpu.emplace_back(std::max(n, 1u));
        gpu.emplace_back(std::max(n, 1u));
    }
    SampleWindow frameCpu(std::max(st.frames, 1u)), frameGpu(std::max(st.frames, 1u));
    const auto ms = [](uint64_t begin, uint64_t end) {
        return end > begin ? double(end - begin) / 1e6 : 0.0;
    };
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (!st.covers(r)) return;
        frameCpu.add(ms(r.cpuBegin, r.cpuEnd));
        if (r.gpuResolved) frameGpu.add(ms(r.gpuBegin, r.gpuEnd));
        FrameProfiler::forEachScopeIn(r, [&](uint16_t scope, double cpuMs, double gpuMs) {
            cpu[scope].add(cpuMs);
            if (gpuMs >= 0.0) gpu[scope].add(gpuMs);
        });
    });
    for (size_t i = 0; i < samples.size(); ++i) {
        st.cpu.push_back(cpu[i].stats());
        st.gpu.push_back(gpu[i].stats());
    }
    st.frameCpu = frameCpu.stats();
    st.frameGpu = frameGpu.stats();
    return st;
}

// "frames 1, 2 and 5" (the first few of a long list).
std::string frameList(const std::vector<uint64_t>& frames) {
    std::string out = frames.size() == 1 ? "frame " : "frames ";
    for (size_t i = 0; i < frames.size() && i < 8; ++i)
        out += (i == 0 ? "" : i + 1 == frames.size() ? " and " : ", ") + std::to_string(frames[i]);
    return frames.size() > 8 ? out + ", ..." : out;
}

// What the statistics leave out, and why.
std::string steadyStateLine(const FrameProfiler& p, const SteadyState& st) {
    const WarmUpCounts& w = p.warmUp();
    if (!w.frames) return "Steady state: every frame (" + std::to_string(st.frames) + "); none warmed up.";
    const std::string why = "made resources or ran a pass for the first time, compiling its pipelines";
    if (!st.reached)
        return "Steady state: not reached. Every recorded frame (" + frameList(st.warmUpFrames) + ") " + why +
               "; the figures include them. Render more frames for a steady-state median.";
    return "Steady state: " + std::to_string(w.frames) + " warm-up frame" + (w.frames == 1 ? "" : "s") +
           " left out of the statistics (" + frameList(st.warmUpFrames) +
           "): they compiled pipelines / made resources (" + std::to_string(w.madeResources) +
           " made or freed GPU resources, " + std::to_string(w.firstRunOfPass) +
           " ran a pass for the first time); the figures are over the " + std::to_string(st.frames) +
           " steady-state frames.";
}

// Frames checked against the budgets and found over, in the frames the statistics cover.
struct BudgetCounts {
    uint64_t checked, over, overGi;
};
BudgetCounts budgetCounts(const FrameProfiler& p, const SteadyState& st) {
    if (!st.reached) return {p.framesChecked(), p.framesOverBudget(), p.framesOverGiBudget()};
    const WarmUpCounts& w = p.warmUp();
    return {p.framesChecked() - w.checked, p.framesOverBudget() - w.overBudget,
            p.framesOverGiBudget() - w.overGiBudget};
}

// "frames checked 60, 2 of them warm-up; over budget 58 of the 58 steady-state frames (...)".
std::string framesCheckedLine(const FrameProfiler& p, const SteadyState& st) {
    const BudgetCounts counts = budgetCounts(p, st);
    return "frames checked " + std::to_string(p.framesChecked()) + ", " + std::to_string(p.warmUp().checked) +
           " of them warm-up; over budget " + std::to_string(counts.over) + " of the " +
           std::to_string(counts.checked) + (st.reached ? " steady-state" : "") +
           " frames (over the GI budget: " + std::to_string(counts.overGi) + ")";
}

// Every GI pass together (the top-level "gi" scopes: gi and gi.rebuild), as the budget check
// adds them, over the checked frames still recorded: the figure the GI budget is held to.
struct GiTotal {
    uint32_t frames = 0;
    double measuredMedian = 0, predictedMedian = 0, x360Median = 0, ps3Median = 0, budgetedMedian = 0;
    double budgetedLast = 0;
    double shareOfGi = 0; // budgetedMedian in percent of the GI budget
};

GiTotal giTotal(const FrameProfiler& p) {
    GiTotal t;
    const SteadyState st = steadyState(p);
    const auto counted = [&](const FrameProfiler::FrameRecord& r) { return r.checked && st.covers(r); };
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) { t.frames += counted(r) ? 1 : 0; });
    if (!t.frames) return t;
    // The profiler's own windowed statistics, sized to hold every checked frame.
    SampleWindow measured(t.frames), predicted(t.frames), x360(t.frames), ps3(t.frames), budgeted(t.frames);
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (!counted(r)) return;
        measured.add(r.check.giMs);
        predicted.add(r.check.giPredictedMs);
        x360.add(r.check.giPredictedX360Ms);
        ps3.add(r.check.giPredictedPs3Ms);
        budgeted.add(r.check.giBudgetedMs);
    });
    t.measuredMedian = measured.stats().median;
    t.predictedMedian = predicted.stats().median;
    t.x360Median = x360.stats().median;
    t.ps3Median = ps3.stats().median;
    t.budgetedMedian = budgeted.stats().median;
    t.budgetedLast = budgeted.stats().last;
    t.shareOfGi = p.profile().giBudgetMs > 0 ? 100.0 * t.budgetedMedian / p.profile().giBudgetMs : 0;
    return t;
}

// "measured" or "predicted x360": what the GI budget holds.
std::string giTimeKind(const FrameProfiler& p) {
    return p.profile().giTimePredicted ? "predicted " + p.profile().name : "measured";
}

// Milliseconds with the digits a small budget needs (0.001 ms is not "0.00").
std::string ms(double v) {
    return fixed(v, v != 0 && std::fabs(v) < 0.1 ? 4 : 2) + " ms";
}

// The GI budget's figure: every GI pass, as the check adds them, over the checked frames.
std::string giTotalLine(const FrameProfiler& p) {
    const GiTotal t = giTotal(p);
    if (!t.frames) return "GI total: no frame checked yet";
    return "GI total (every GI pass, the " + giTimeKind(p) + " time the GI budget holds): median " +
           ms(t.budgetedMedian) + " of the " + ms(p.profile().giBudgetMs) + " budget (" +
           fixed(t.shareOfGi, 1) + "%), last checked frame " + ms(t.budgetedLast) +
           (p.profile().giTimePredicted ? "; measured median " + ms(t.measuredMedian) : "");
}

std::vector<Row> rows(const FrameProfiler& p) {
    const SteadyState st = steadyState(p);
    std::vector<Row> out;
    for (const ScopeInfo& s : p.scopes()) {
        const size_t index = size_t(&s - p.scopes().data());
        const FrameProfiler::ScopePrediction predicted = p.predicted(index);
        // A pass that ran only in warm-up frames (a rebuild) keeps those figures, marked.
        const bool warmUpOnly = st.cpu[index].count == 0 && st.gpu[index].count == 0;
        Row r{&s,
              warmUpOnly ? s.cpuMs.stats() : st.cpu[index],
              warmUpOnly ? s.gpuMs.stats() : st.gpu[index],
              predicted.x360,
              predicted.ps3,
              predicted.active,
              s.path.starts_with("gi"),
              0,
              0,
              0,
              warmUpOnly && st.reached};
        const double t = r.gpu.count ? r.gpu.median : r.cpu.median;
        r.shareOfFrame = p.profile().frameBudgetMs > 0 ? 100.0 * t / p.profile().frameBudgetMs : 0;
        r.shareOfGi =
            s.path.starts_with("gi") && p.profile().giBudgetMs > 0 ? 100.0 * t / p.profile().giBudgetMs : 0;
        if (r.gi && p.profile().giBudgetMs > 0 && p.profile().giTimePredicted)
            r.predictedShareOfGi = 100.0 * r.active.ms / p.profile().giBudgetMs;
        out.push_back(r);
    }
    // Children follow their parent.
    std::vector<Row> ordered;
    for (size_t i : p.scopesInTreeOrder())
        ordered.push_back(out[i]);
    return ordered;
}

// The commands of the newest steady-state frame (any frame before steady state is reached): the
// frame's totals and its top-level GI scopes' (their stages: the GI's dependent-pass chain).
struct FrameCommands {
    bool any = false;
    uint64_t frame = 0;
    rhi::CommandCounts total, gi;
};

FrameCommands frameCommands(const FrameProfiler& p) {
    const SteadyState st = steadyState(p);
    FrameCommands out;
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (!st.covers(r)) return;
        out.any = true;
        out.frame = r.frame;
        out.total = r.commands;
        out.gi = {};
        for (uint32_t k = 0; k < r.sampleCount; ++k) {
            const ScopeInfo& scope = p.scopes()[r.samples[k].scope];
            if (scope.depth == 0 && scope.path.starts_with("gi")) out.gi += r.samples[k].commands;
        }
    });
    return out;
}

std::string commandsLine(const FrameProfiler& p) {
    const FrameCommands c = frameCommands(p);
    if (!c.any) return "Commands per frame: no frame recorded";
    return "Commands per frame (frame " + std::to_string(c.frame) +
           "): " + std::to_string(c.total.dispatches) + " dispatches, " + std::to_string(c.total.allDraws()) +
           " draws (" + std::to_string(c.total.drawsIndexed) + " indexed), " +
           std::to_string(c.total.barriers) + " barriers, " + std::to_string(c.total.stages) +
           " serial stages. GI dependent-pass chain: " + std::to_string(c.gi.stages) +
           " stages (runs of GI dispatches and draws between barriers) of " +
           std::to_string(c.gi.dispatches) + " dispatches, " + std::to_string(c.gi.allDraws()) +
           " draws and " + std::to_string(c.gi.barriers) + " barriers";
}

std::string commandArgs(const rhi::CommandCounts& c) {
    return "{\"dispatches\":" + std::to_string(c.dispatches) + ",\"draws\":" + std::to_string(c.allDraws()) +
           ",\"barriers\":" + std::to_string(c.barriers) + ",\"stages\":" + std::to_string(c.stages) + "}";
}

uint64_t giMemory(const FrameProfiler& p) {
    return p.allocations().bytesIn("gi");
}

// A pass is over budget when its median alone exceeds the frame budget, or, for GI passes, the
// GI budget, or on a profile whose GI time is predicted when its predicted time does.
bool overBudget(const Row& r) {
    if (r.warmUpOnly) return false;
    return r.shareOfFrame > 100.0 || r.shareOfGi > 100.0 || r.predictedShareOfGi > 100.0;
}

// The budget column: OVER, ok, or warm-up for a pass that ran in warm-up frames only.
const char* budgetWord(const Row& r) {
    return overBudget(r) ? "OVER" : r.warmUpOnly ? "warm-up" : "ok";
}

// Notes grouped by topic, topics in the order they first appear.
using NoteGroups = std::vector<std::pair<std::string, std::vector<const FrameProfiler::Note*>>>;
NoteGroups notesByTopic(const FrameProfiler& p) {
    NoteGroups groups;
    p.forEachNote([&](const FrameProfiler::Note& n) {
        auto it =
            std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == n.topic(); });
        if (it == groups.end()) it = groups.insert(groups.end(), {std::string(n.topic()), {}});
        it->second.push_back(&n);
    });
    return groups;
}

std::string droppedNotes(const FrameProfiler& p) {
    return p.notesDropped() ? "(" + std::to_string(p.notesDropped()) + " older notes dropped)\n" : "";
}

std::string csvQuote(std::string_view s) {
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string markdownCell(std::string_view s) {
    std::string out;
    for (char c : s)
        out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

} // namespace

std::string profileSummaryText(const FrameProfiler& p) {
    std::ostringstream o;
    const auto& prof = p.profile();
    o << "Frame profile: platform " << prof.name << " (frame budget " << ms(prof.frameBudgetMs) << ", GI "
      << ms(prof.giBudgetMs) << ", GI memory " << mib(prof.giMemoryBudgetBytes) << ")\n";
    const SteadyState st = steadyState(p);
    o << steadyStateLine(p, st) << "\n";
    o << "GPU timing source: " << gpuSourceName(p) << "; " << framesCheckedLine(p, st) << "\n";
    const SampleStats fc = st.frameCpu, fg = st.frameGpu;
    o << "frame: cpu median " << fixed(fc.median) << " ms (p95 " << fixed(fc.p95) << ")";
    if (fg.count) o << ", gpu median " << fixed(fg.median) << " ms (p95 " << fixed(fg.p95) << ")";
    o << "\n" << giTotalLine(p) << "\n\n";
    // The GI columns give each GI pass's share of the GI budget: measured, and on a profile that
    // holds GI to its predicted time, predicted too (either over 100% makes the pass OVER).
    const std::string predictedColumn =
        predictedProfile(p).empty() ? "" : std::string(predictedProfile(p)) + " GI %";
    char line[512];
    std::snprintf(line, sizeof(line), "%-28s %9s %9s %9s %9s %9s %9s %8s %8s %8s %10s %s\n", "pass",
                  "cpu med", "gpu last", "gpu med", "gpu p95", "gpu max", "x360 ms", "ps3 ms", "frame %",
                  "GI %", predictedColumn.c_str(), "budget");
    o << line;
    const auto percent = [](double v, bool shown) { return shown ? fixed(v, 1) + "%" : std::string("-"); };
    for (const Row& r : rows(p)) {
        const std::string name = std::string(2 * r.scope->depth, ' ') + r.scope->name;
        std::snprintf(
            line, sizeof(line), "%-28s %9.3f %9s %9s %9s %9s %9.3f %8.3f %7.1f%% %8s %10s %s\n", name.c_str(),
            r.cpu.median, r.gpu.count ? fixed(r.gpu.last).c_str() : "-",
            r.gpu.count ? fixed(r.gpu.median).c_str() : "-", r.gpu.count ? fixed(r.gpu.p95).c_str() : "-",
            r.gpu.count ? fixed(r.gpu.max).c_str() : "-", r.x360.ms, r.ps3.ms, r.shareOfFrame,
            percent(r.shareOfGi, r.gi).c_str(),
            percent(r.predictedShareOfGi, r.gi && p.profile().giTimePredicted).c_str(), budgetWord(r));
        o << line;
    }
    o << "\nmemory by category (current / peak):\n";
    for (const auto& [category, usage] : p.allocations().categories())
        o << "  " << category << ": " << mib(usage.currentBytes) << " / " << mib(usage.peakBytes) << "\n";
    o << "  GI total: " << mib(giMemory(p)) << " of " << mib(prof.giMemoryBudgetBytes) << " budget"
      << (giMemory(p) > prof.giMemoryBudgetBytes ? " (OVER BUDGET)" : "") << "\n";
    o << "  all: " << mib(p.allocations().totalBytes()) << " (peak " << mib(p.allocations().peakTotalBytes())
      << ") of the platform's " << mib(prof.gpuMemoryBytes) << " of GPU memory"
      << (p.allocations().peakTotalBytes() > prof.gpuMemoryBytes ? " (OVER)" : "") << "\n";
    for (const auto& [topic, notes] : notesByTopic(p)) {
        o << "\n" << topic << ":\n";
        for (const auto* n : notes)
            o << "  frame " << n->frame << ": " << n->text() << "\n";
    }
    o << droppedNotes(p);
    return o.str();
}

std::string profileShortSummary(const FrameProfiler& p, const std::string& fullReport) {
    std::ostringstream o;
    const auto& prof = p.profile();
    const SteadyState st = steadyState(p);
    const std::vector<Row> all = rows(p);
    o << "Frame profile: platform " << prof.name << ", " << st.frames
      << (st.reached ? " steady-state frames" : " frames, no steady state yet");
    if (st.reached && p.warmUp().frames)
        o << " (" << p.warmUp().frames << " warm-up frame" << (p.warmUp().frames == 1 ? "" : "s")
          << " left out: they compiled pipelines / made resources)";
    o << "\n";
    const bool gpu = st.frameGpu.count > 0;
    const double frameMs = gpu ? st.frameGpu.median : st.frameCpu.median;
    o << "  frame: median " << ms(frameMs) << " (" << (gpu ? gpuSourceName(p) : std::string("cpu"))
      << ") of the " << ms(prof.frameBudgetMs)
      << " budget: " << (frameMs > prof.frameBudgetMs ? "OVER" : "ok") << "\n";
    const bool giRan = std::any_of(all.begin(), all.end(), [](const Row& r) { return r.gi; });
    const GiTotal t = giTotal(p);
    if (!giRan)
        o << "  GI: off (no GI pass ran)\n";
    else if (t.frames)
        o << "  GI: median " << ms(t.budgetedMedian) << " (" << giTimeKind(p) << ") of the "
          << ms(prof.giBudgetMs) << " budget (" << fixed(t.shareOfGi, 1)
          << "%): " << (t.shareOfGi > 100.0 ? "OVER" : "ok") << "\n";
    // The costliest passes: those with no pass inside them, by median.
    std::vector<const Row*> leaves;
    for (const Row& r : all) {
        const int32_t index = int32_t(r.scope - p.scopes().data());
        const bool parent = std::any_of(p.scopes().begin(), p.scopes().end(),
                                        [&](const ScopeInfo& s) { return s.parent == index; });
        if (!parent && !r.warmUpOnly) leaves.push_back(&r);
    }
    const auto median = [](const Row* r) { return r->gpu.count ? r->gpu.median : r->cpu.median; };
    std::sort(leaves.begin(), leaves.end(),
              [&](const Row* a, const Row* b) { return median(a) > median(b); });
    o << "  costliest passes:";
    for (size_t i = 0; i < leaves.size() && i < 3; ++i)
        o << (i ? ", " : " ") << leaves[i]->scope->path << " " << ms(median(leaves[i]));
    o << "\n  memory: " << mib(p.allocations().totalBytes()) << " of the platform's "
      << mib(prof.gpuMemoryBytes) << (p.allocations().peakTotalBytes() > prof.gpuMemoryBytes ? " (OVER)" : "")
      << "; GI total: " << mib(giMemory(p)) << " of " << mib(prof.giMemoryBudgetBytes) << " budget"
      << (giMemory(p) > prof.giMemoryBudgetBytes ? " (OVER BUDGET)" : "") << "\n";
    o << "  " << framesCheckedLine(p, st) << "\n";
    o << (fullReport.empty() ? std::string("The full report: --profile-out DIR writes it (summary.md)")
                             : "The full report: " + fullReport)
      << "\n";
    return o.str();
}

std::string profileSummaryMarkdown(const FrameProfiler& p) {
    std::ostringstream o;
    const auto& prof = p.profile();
    o << "# Frame profile\n\nPlatform `" << prof.name << "`: frame budget " << ms(prof.frameBudgetMs)
      << ", GI budget " << ms(prof.giBudgetMs) << ", GI memory budget " << mib(prof.giMemoryBudgetBytes)
      << ".\n"
      << steadyStateLine(p, steadyState(p)) << "\nGPU timing source: `" << gpuSourceName(p) << "`; "
      << framesCheckedLine(p, steadyState(p)) << ".\n"
      << giTotalLine(p) << "\n"
      << commandsLine(p) << ".\n\n";
    o << "| pass | timing | cpu median ms | gpu last | gpu mean | gpu median | gpu p95 | gpu max | predicted "
         "x360 ms | "
         "predicted ps3 ms | bottleneck (x360) | share of frame | share of GI budget | budget | dispatches | "
         "draws | barriers | stages |\n";
    o << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows(p)) {
        o << "| " << std::string(r.scope->depth * 2, ' ') << r.scope->path << " | " << timingOf(p, r) << " | "
          << fixed(r.cpu.median) << " | ";
        if (r.gpu.count)
            o << fixed(r.gpu.last) << " | " << fixed(r.gpu.mean) << " | " << fixed(r.gpu.median) << " | "
              << fixed(r.gpu.p95) << " | " << fixed(r.gpu.max) << " | ";
        else
            o << "- | - | - | - | - | ";
        o << fixed(r.x360.ms) << " | " << fixed(r.ps3.ms) << " | " << r.x360.bottleneck << " | "
          << fixed(r.shareOfFrame, 1) << "% | " << (r.gi ? fixed(r.shareOfGi, 1) + "%" : "-");
        if (r.gi && p.profile().giTimePredicted)
            o << " (predicted " << markdownCell(predictedProfile(p)) << ": " << fixed(r.predictedShareOfGi, 1)
              << "%)";
        const rhi::CommandCounts& c = r.scope->commands;
        o << " | " << (overBudget(r) ? "**OVER**" : budgetWord(r)) << " | " << c.dispatches << " | "
          << c.allDraws() << " | " << c.barriers << " | " << c.stages << " |\n";
    }
    // The GI budget holds every GI pass together, gi.rebuild included: the row the check reads.
    const GiTotal t = giTotal(p);
    if (t.frames) {
        const double measuredShare =
            p.profile().giBudgetMs > 0 ? 100.0 * t.measuredMedian / p.profile().giBudgetMs : 0;
        o << "| **GI total** (every GI pass, per checked frame) | budget check | - | - | - | "
          << fixed(t.measuredMedian) << " | - | - | " << fixed(t.x360Median) << " | " << fixed(t.ps3Median)
          << " | - | "
          << fixed(p.profile().frameBudgetMs > 0 ? 100.0 * t.measuredMedian / p.profile().frameBudgetMs : 0,
                   1)
          << "% | " << fixed(measuredShare, 1) << "%";
        if (p.profile().giTimePredicted)
            o << " (predicted " << markdownCell(predictedProfile(p)) << ": " << fixed(t.shareOfGi, 1) << "%)";
        const FrameCommands c = frameCommands(p);
        o << " | " << (measuredShare > 100.0 || t.shareOfGi > 100.0 ? "**OVER**" : "ok") << " | "
          << c.gi.dispatches << " | " << c.gi.allDraws() << " | " << c.gi.barriers << " | " << c.gi.stages
          << " |\n";
    }
    o << "\n## Memory\n\n| category | current | peak | resources |\n|---|---|---|---|\n";
    for (const auto& [category, usage] : p.allocations().categories())
        o << "| " << category << " | " << mib(usage.currentBytes) << " | " << mib(usage.peakBytes) << " | "
          << usage.count << " |\n";
    o << "\nGI memory: " << mib(giMemory(p)) << " of " << mib(prof.giMemoryBudgetBytes)
      << (giMemory(p) > prof.giMemoryBudgetBytes ? " (**over budget**)" : "") << ".\n";
    o << "All memory: " << mib(p.allocations().totalBytes()) << " (peak "
      << mib(p.allocations().peakTotalBytes()) << ") of the platform's " << mib(prof.gpuMemoryBytes)
      << " of GPU memory" << (p.allocations().peakTotalBytes() > prof.gpuMemoryBytes ? " (**over**)" : "")
      << ".\n";
    for (const auto& [topic, notes] : notesByTopic(p)) {
        o << "\n## " << topic << "\n\n| frame | note |\n|---|---|\n";
        for (const auto* n : notes)
            o << "| " << n->frame << " | " << markdownCell(n->text()) << " |\n";
    }
    if (p.notesDropped()) o << "\n" << droppedNotes(p);
    return o.str();
}

std::string profileSummaryCsv(const FrameProfiler& p) {
    std::ostringstream o;
    o << "pass,depth,timing_source,cpu_median_ms,gpu_last_ms,gpu_mean_ms,gpu_median_ms,gpu_p95_ms,gpu_max_ms,"
         "predicted_x360_ms,predicted_ps3_ms,share_of_frame_pct,share_of_gi_pct,predicted_share_of_gi_pct,"
         "dispatches,draws,draws_indexed,barriers,stages\n";
    for (const Row& r : rows(p)) {
        o << r.scope->path << "," << r.scope->depth << "," << timingOf(p, r) << "," << fixed(r.cpu.median, 4)
          << "," << fixed(r.gpu.last, 4) << "," << fixed(r.gpu.mean, 4) << "," << fixed(r.gpu.median, 4)
          << "," << fixed(r.gpu.p95, 4) << "," << fixed(r.gpu.max, 4) << "," << fixed(r.x360.ms, 4) << ","
          << fixed(r.ps3.ms, 4) << "," << fixed(r.shareOfFrame, 2) << "," << fixed(r.shareOfGi, 2) << ","
          << fixed(r.predictedShareOfGi, 2) << "," << r.scope->commands.dispatches << ","
          << r.scope->commands.allDraws() << "," << r.scope->commands.drawsIndexed << ","
          << r.scope->commands.barriers << "," << r.scope->commands.stages << "\n";
    }
    const FrameCommands c = frameCommands(p);
    o << "\ncommands,frame,dispatches,draws,draws_indexed,barriers,stages\n";
    for (const auto& [what, n] : {std::pair{"frame", c.total}, std::pair{"gi", c.gi}})
        o << what << "," << c.frame << "," << n.dispatches << "," << n.allDraws() << "," << n.drawsIndexed
          << "," << n.barriers << "," << n.stages << "\n";
    const GiTotal t = giTotal(p);
    o << "\ngi_total,checked_frames,measured_median_ms,predicted_median_ms,predicted_x360_median_ms,"
         "predicted_ps3_median_ms,budgeted_median_ms,gi_budget_ms,share_of_gi_pct,time_held\n";
    o << "gi," << t.frames << "," << fixed(t.measuredMedian, 4) << "," << fixed(t.predictedMedian, 4) << ","
      << fixed(t.x360Median, 4) << "," << fixed(t.ps3Median, 4) << "," << fixed(t.budgetedMedian, 4) << ","
      << fixed(p.profile().giBudgetMs, 4) << "," << fixed(t.shareOfGi, 2) << "," << csvQuote(giTimeKind(p))
      << "\n";
    const SteadyState st = steadyState(p);
    o << "\nsteady_state,statistics_frames,warm_up_frames_left_out,made_resources,first_run_of_pass\n";
    o << (st.reached ? "reached" : "not_reached") << "," << st.frames << ","
      << (st.reached ? p.warmUp().frames : 0) << "," << p.warmUp().madeResources << ","
      << p.warmUp().firstRunOfPass << "\n";
    o << "\ncategory,current_bytes,peak_bytes,resources\n";
    for (const auto& [category, usage] : p.allocations().categories())
        o << category << "," << usage.currentBytes << "," << usage.peakBytes << "," << usage.count << "\n";
    bool header = false;
    p.forEachNote([&](const FrameProfiler::Note& n) {
        if (!std::exchange(header, true)) o << "\nframe,topic,note\n";
        o << n.frame << "," << csvQuote(n.topic()) << "," << csvQuote(n.text()) << "\n";
    });
    return o.str();
}

std::string profileTraceJson(const FrameProfiler& p) {
    std::ostringstream o;
    uint64_t origin = 0;
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (!origin) origin = r.cpuBegin;
    });
    const auto us = [&](uint64_t ns) { return fixed(double(ns - std::min(ns, origin)) / 1000.0, 3); };
    const std::string gpuTrack = "GPU (" + gpuSourceName(p) + ")";
    o << "{\"displayTimeUnit\":\"ms\",\"traceEvents\":[\n";
    o << R"({"name":"process_name","ph":"M","pid":1,"args":{"name":"LPV Engine"}},)"
      << "\n";
    o << R"({"name":"thread_name","ph":"M","pid":1,"tid":1,"args":{"name":"CPU"}},)"
      << "\n";
    o << R"({"name":"thread_name","ph":"M","pid":1,"tid":2,"args":{"name":")" << jsonEscape(gpuTrack)
      << "\"}}";
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (!r.cpuEnd) return;
        o << ",\n{\"name\":\"frame " << r.frame
          << "\",\"ph\":\"X\",\"pid\":1,\"tid\":1,\"ts\":" << us(r.cpuBegin)
          << ",\"dur\":" << fixed(double(r.cpuEnd - r.cpuBegin) / 1000.0);
        if (r.warmUp)
            o << ",\"args\":{\"warm_up\":true,\"made_resources\":"
              << (r.warmUp & kWarmUpMadeResources ? "true" : "false")
              << ",\"first_run_of_pass\":" << (r.warmUp & kWarmUpFirstRunOfPass ? "true" : "false") << "}";
        o << "}";
        // GPU times are on the device's clock: place them relative to the frame's CPU start.
        const auto gpuTs = [&](uint64_t t) { return us(r.cpuBegin + (t - r.gpuBegin)); };
        if (r.gpuResolved)
            o << ",\n{\"name\":\"frame " << r.frame
              << "\",\"ph\":\"X\",\"pid\":1,\"tid\":2,\"ts\":" << gpuTs(r.gpuBegin)
              << ",\"dur\":" << fixed(double(r.gpuEnd - r.gpuBegin) / 1000.0) << "}";
        for (uint32_t k = 0; k < r.sampleCount; ++k) {
            const auto& s = r.samples[k];
            const std::string name = jsonEscape(p.scopes()[s.scope].path);
            o << ",\n{\"name\":\"" << name << "\",\"ph\":\"X\",\"pid\":1,\"tid\":1,\"ts\":" << us(s.cpuBegin)
              << ",\"dur\":" << fixed(double(s.cpuEnd - s.cpuBegin) / 1000.0)
              << ",\"args\":" << commandArgs(s.commands) << "}";
            if (r.gpuResolved && s.gpuTimed && s.gpuEnd >= s.gpuBegin)
                o << ",\n{\"name\":\"" << name
                  << "\",\"ph\":\"X\",\"pid\":1,\"tid\":2,\"ts\":" << gpuTs(s.gpuBegin)
                  << ",\"dur\":" << fixed(double(s.gpuEnd - s.gpuBegin) / 1000.0) << "}";
        }
        o << ",\n{\"name\":\"commands\",\"ph\":\"C\",\"pid\":1,\"ts\":" << us(r.cpuBegin)
          << ",\"args\":" << commandArgs(r.commands) << "}";
        o << ",\n{\"name\":\"memory\",\"ph\":\"C\",\"pid\":1,\"ts\":" << us(r.cpuBegin)
          << ",\"args\":{\"total_bytes\":" << r.memoryTotal << ",\"gi_bytes\":" << r.memoryGi << "}}";
        if (r.checked) {
            o << ",\n{\"name\":\"budget\",\"ph\":\"C\",\"pid\":1,\"ts\":" << us(r.cpuBegin)
              << ",\"args\":{\"frame_ms\":" << fixed(r.check.frameMs)
              << ",\"frame_budget_ms\":" << fixed(p.profile().frameBudgetMs)
              << ",\"gi_ms\":" << fixed(r.check.giMs)
              << ",\"gi_budget_ms\":" << fixed(p.profile().giBudgetMs);
            // On a profile whose GI time is predicted the check holds that time to the budget too.
            if (!predictedProfile(p).empty()) o << ",\"gi_predicted_ms\":" << fixed(r.check.giBudgetedMs);
            o << "}}";
        }
    });
    // Notes as global instant events (a vertical line across the tracks), the text as the name.
    p.forEachNote([&](const FrameProfiler::Note& n) {
        // A note whose frame is older than the trace's frames goes at the trace's start, marked so.
        const bool before = n.cpuTime < origin;
        o << ",\n{\"name\":\"" << jsonEscape(std::string(n.text())) << "\",\"cat\":\""
          << jsonEscape(std::string(n.topic()))
          << "\",\"ph\":\"i\",\"s\":\"g\",\"pid\":1,\"tid\":1,\"ts\":" << us(n.cpuTime)
          << ",\"args\":{\"frame\":" << n.frame << ",\"topic\":\"" << jsonEscape(std::string(n.topic()))
          << "\"" << (before ? ",\"before_trace\":true" : "") << "}}";
    });
    o << "\n]}\n";
    return o.str();
}

std::string profileChartSvg(const FrameProfiler& p) {
    // Steady-state frames only: a warm-up frame (seconds of pipeline compiles) would flatten the rest.
    const SteadyState st = steadyState(p);
    std::vector<const FrameProfiler::FrameRecord*> frames;
    p.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (r.checked && st.covers(r)) frames.push_back(&r);
    });
    const double width = 1000, height = 360, left = 60, top = 30, plotW = width - left - 200,
                 plotH = height - top - 40;
    double maxMs = p.profile().frameBudgetMs * 1.2;
    for (const auto* r : frames)
        maxMs = std::max(maxMs, r->check.frameMs * 1.05);
    static const char* kColors[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                    "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    o << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    o << "<text x=\"" << left << "\" y=\"18\" font-size=\"13\">Per-frame pass times (" << gpuSourceName(p)
      << " where resolved, else CPU), platform " << xmlEscape(p.profile().name) << "</text>\n";
    std::map<uint64_t, std::string> notesOfFrame;
    p.forEachNote([&](const FrameProfiler::Note& n) {
        std::string& t = notesOfFrame[n.frame];
        t += (t.empty() ? "" : "; ") + std::string(n.text());
    });
    const double barW = frames.empty() ? 1 : plotW / double(frames.size());
    const auto y = [&](double v) { return top + plotH - v / maxMs * plotH; };
    for (size_t i = 0; i < frames.size(); ++i) {
        const auto& r = *frames[i];
        double acc = 0;
        for (uint32_t k = 0; k < r.sampleCount; ++k) {
            const auto& s = r.samples[k];
            if (p.scopes()[s.scope].depth != 0) continue;
            const double t = r.gpuResolved && s.gpuTimed ? double(s.gpuEnd - s.gpuBegin) / 1e6
                                                         : double(s.cpuEnd - s.cpuBegin) / 1e6;
            o << "<rect x=\"" << fixed(left + double(i) * barW, 2) << "\" y=\"" << fixed(y(acc + t), 2)
              << "\" width=\"" << fixed(std::max(barW - 0.5, 0.5), 2) << "\" height=\""
              << fixed(t / maxMs * plotH, 2) << "\" fill=\"" << kColors[s.scope % 10] << "\"/>\n";
            acc += t;
        }
        const bool over = r.check.frameOverBudget || r.check.giOverBudget || r.check.giPredictedOverBudget;
        if (over)
            o << "<rect x=\"" << fixed(left + double(i) * barW, 2) << "\" y=\"" << top - 6 << "\" width=\""
              << fixed(std::max(barW - 0.5, 0.5), 2) << "\" height=\"4\" fill=\"red\"><title>frame "
              << r.frame << " over budget</title></rect>\n";
        if (const auto note = notesOfFrame.find(r.frame); note != notesOfFrame.end())
            o << "<rect x=\"" << fixed(left + double(i) * barW, 2) << "\" y=\"" << top + plotH + 2
              << "\" width=\"" << fixed(std::max(barW - 0.5, 0.5), 2)
              << "\" height=\"4\" fill=\"#4e79a7\"><title>frame " << r.frame << ": "
              << xmlEscape(note->second) << "</title></rect>\n";
    }
    o << "<line x1=\"" << left << "\" x2=\"" << left + plotW << "\" y1=\""
      << fixed(y(p.profile().frameBudgetMs), 2) << "\" y2=\"" << fixed(y(p.profile().frameBudgetMs), 2)
      << "\" stroke=\"red\" stroke-dasharray=\"6 3\"/>\n";
    o << "<text x=\"" << left + plotW + 4 << "\" y=\"" << fixed(y(p.profile().frameBudgetMs) + 4, 2)
      << "\" fill=\"red\">frame budget " << fixed(p.profile().frameBudgetMs, 1) << " ms</text>\n";
    o << "<line x1=\"" << left << "\" x2=\"" << left << "\" y1=\"" << top << "\" y2=\"" << top + plotH
      << "\" stroke=\"black\"/>\n";
    for (int t = 0; t <= 4; ++t) {
        const double v = maxMs * t / 4;
        o << "<text x=\"" << left - 6 << "\" y=\"" << fixed(y(v) + 4, 2) << "\" text-anchor=\"end\">"
          << fixed(v, 1) << "</text>\n";
    }
    o << "<text x=\"" << left << "\" y=\"" << height - 10 << "\">frames (" << frames.size()
      << "); red marks: over budget; blue marks: notes (hover); ms on the left axis";
    if (st.reached && !st.warmUpFrames.empty())
        o << "; " << st.warmUpFrames.size() << " warm-up frames left out";
    // The chart holds the last traceFrames frames; notes of frames before them are still counted.
    const uint64_t firstShown = frames.empty() ? UINT64_MAX : frames.front()->frame;
    const size_t earlier = size_t(std::count_if(notesOfFrame.begin(), notesOfFrame.end(),
                                                [&](const auto& n) { return n.first < firstShown; }));
    if (earlier) o << "; notes on " << earlier << " earlier frames: summary.md";
    o << "</text>\n";
    int legend = 0;
    for (size_t i = 0; i < p.scopes().size(); ++i) {
        if (p.scopes()[i].depth != 0) continue;
        const double ly = top + 16.0 * legend++;
        o << "<rect x=\"" << left + plotW + 10 << "\" y=\"" << ly + 20
          << "\" width=\"10\" height=\"10\" fill=\"" << kColors[i % 10] << "\"/><text x=\""
          << left + plotW + 24 << "\" y=\"" << ly + 29 << "\">" << xmlEscape(p.scopes()[i].name)
          << "</text>\n";
    }
    o << "</svg>\n";
    return o.str();
}

void writeProfileOutputs(const FrameProfiler& p, const std::string& directory) {
    platforms::Platform::createDirectories(directory);
    const std::string texts[] = {profileTraceJson(p), profileSummaryMarkdown(p), profileSummaryCsv(p),
                                 profileChartSvg(p)};
    static_assert(std::size(texts) == kProfileOutputFiles.size());
    // One file that cannot be written does not cost the others.
    std::string failures;
    for (size_t i = 0; i < kProfileOutputFiles.size(); ++i) {
        try {
            platforms::Platform::writeFile(directory + "/" + kProfileOutputFiles[i], texts[i]);
        } catch (const std::runtime_error& e) {
            failures += (failures.empty() ? "" : "; ") + std::string(e.what());
        }
    }
    if (!failures.empty()) throw std::runtime_error(failures);
}

} // namespace lpv::engine
