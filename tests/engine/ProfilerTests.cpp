// Frame profiler on the null device, whose simulated timestamps cost 1 us per command and become
// readable framesInFlight frames later - the same latency rule as a real device.
#include "engine/profiler/CostModel.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfileReport.h"
#include "platforms/PlatformProfile.h"
#include "rhi/Device.h"

#include "../support/TestDevice.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

using namespace lpv;
using namespace lpv::engine;

namespace {

using test::nullDevice;

// A profile with tiny budgets so simulated microseconds can cross them.
platforms::PlatformProfile tinyProfile(double frameMs, double giMs) {
    auto p = platforms::loadPlatformProfile("pc");
    p.name = "test";
    p.frameBudgetMs = frameMs;
    p.giBudgetMs = giMs;
    return p;
}

// One frame: `renderDispatches` inside render/gbuffer, `giDispatches` inside gi/propagate.
void frame(rhi::Device& device, FrameProfiler& profiler, int renderDispatches, int giDispatches) {
    rhi::CommandList& cmd = device.beginFrame();
    profiler.beginFrame(cmd);
    {
        auto render = profiler.scope("render", &cmd);
        auto gbuffer = profiler.scope("gbuffer", &cmd);
        for (int i = 0; i < renderDispatches; ++i)
            cmd.dispatch(1);
    }
    {
        auto gi = profiler.scope("gi", &cmd);
        auto propagate = profiler.scope("propagate", &cmd);
        WorkCounts w;
        w.aluOps = 240'000'000; // 1 ms on Xbox 360's 240 GFLOPS
        profiler.setWork(w);
        for (int i = 0; i < giDispatches; ++i)
            cmd.dispatch(1);
    }
    profiler.endFrame(cmd);
    device.endFrame();
}

} // namespace

TEST_CASE("profiler: scopes nest, get paths and close") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    frame(*device, profiler, 1, 1);
    REQUIRE(profiler.scopes().size() == 4);
    CHECK(profiler.scopes()[1].path == "render/gbuffer");
    CHECK(profiler.scopes()[1].depth == 1);
    CHECK(profiler.scopes()[3].path == "gi/propagate");
    CHECK(profiler.openScopes() == 0);
    frame(*device, profiler, 1, 1);
    CHECK(profiler.scopes().size() == 4); // the same names are the same scopes next frame
    CHECK(profiler.scopes()[1].cpuMs.count() == 2);

    rhi::CommandList& cmd = device->beginFrame();
    profiler.beginFrame(cmd);
    {
        auto open = profiler.scope("unclosed", &cmd);
        CHECK_THROWS_AS(profiler.endFrame(cmd), std::logic_error);
    }
    profiler.endFrame(cmd);
    device->endFrame();
    CHECK_THROWS_AS(profiler.setWork({}), std::logic_error); // no open scope
}

TEST_CASE("profiler: GPU results arrive frames later, never by waiting") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    CHECK(profiler.gpuTimingSource() == rhi::TimestampSource::Simulated);
    frame(*device, profiler, 3, 2); // frame 1
    const ScopeInfo& gbuffer = profiler.scopes()[1];
    CHECK(gbuffer.gpuMs.count() == 0);
    frame(*device, profiler, 3, 2); // frame 2: frame 1 still in flight
    CHECK(gbuffer.gpuMs.count() == 0);
    CHECK(profiler.framesChecked() == 0);
    frame(*device, profiler, 3, 2); // frame 3 began after frame 1 completed
    REQUIRE(gbuffer.gpuMs.count() == 1);
    CHECK(gbuffer.gpuMs.stats().last == doctest::Approx(0.003)); // three dispatches, 1 us each
    CHECK(profiler.scopes()[3].gpuMs.stats().last == doctest::Approx(0.002));
    CHECK(profiler.framesChecked() == 1);
    CHECK(profiler.lastBudgetCheck().frameMs == doctest::Approx(0.005));
    CHECK(profiler.gpuResultsLost() == 0);
}

// A scope a frame enters more than once (a cascade's, whose passes run phase by phase with the
// other cascades') is one sample of that frame, its time the sum of its entries.
TEST_CASE("profiler: a scope entered twice in a frame counts once, with both entries' time") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    for (int i = 0; i < 4; ++i) {
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        {
            auto gi = profiler.scope("gi", &cmd);
            for (int entry : {2, 3}) {
                auto cascade = profiler.scope("cascade0", &cmd);
                for (int d = 0; d < entry; ++d)
                    cmd.dispatch(1);
            }
        }
        profiler.endFrame(cmd);
        device->endFrame();
    }
    profiler.collectPending();
    const ScopeInfo& cascade = profiler.scopes()[1];
    REQUIRE(cascade.path == "gi/cascade0");
    CHECK(cascade.cpuMs.count() == 4);
    REQUIRE(cascade.gpuMs.count() == 4);
    CHECK(cascade.gpuMs.stats().last == doctest::Approx(0.005)); // 2 + 3 dispatches, 1 us each
    CHECK(cascade.commands.dispatches == 5);
}

// Passes a frame runs phase by phase (each cascade's RSM, then each one's VPLs) are listed under
// their parent, in the order first opened.
TEST_CASE("profiler: scopes in tree order list each one's children after it") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    rhi::CommandList& cmd = device->beginFrame();
    profiler.beginFrame(cmd);
    for (const char* pass : {"rsm", "vpl"})
        for (const char* cascade : {"cascade1", "cascade0"}) {
            auto c = profiler.scope(cascade, &cmd);
            auto p = profiler.scope(pass, &cmd);
        }
    profiler.endFrame(cmd);
    device->endFrame();
    std::vector<std::string> paths;
    for (size_t i : profiler.scopesInTreeOrder())
        paths.push_back(profiler.scopes()[i].path);
    CHECK(paths == std::vector<std::string>{"cascade1", "cascade1/rsm", "cascade1/vpl", "cascade0",
                                            "cascade0/rsm", "cascade0/vpl"});
}

// Before a report the last frames' results are collected without counting the empty device
// frames that carry them in: every recorded frame is checked, none is lost, and the frame
// statistics hold those frames alone (the empty ones took about 0 ms and pulled the median down).
TEST_CASE("profiler: collecting the last frames' results adds no frames") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    for (int i = 0; i < 4; ++i)
        frame(*device, profiler, 3, 2);
    CHECK(profiler.framesChecked() == 2); // two still in flight
    profiler.collectPending();
    CHECK(profiler.framesChecked() == 4);
    CHECK(profiler.gpuResultsLost() == 0);
    const SampleStats gpu = profiler.frameGpuMs(), cpu = profiler.frameCpuMs();
    CHECK(gpu.count == 4);
    CHECK(cpu.count == 4);
    CHECK(gpu.median == doctest::Approx(0.005)); // five dispatches, 1 us each
    size_t recorded = 0;
    profiler.forEachFrame([&](const FrameProfiler::FrameRecord&) { ++recorded; });
    CHECK(recorded == 4);
    CHECK(profiler.scopes()[1].gpuMs.count() == 4);
}

TEST_CASE("profiler: statistics over the window") {
    SampleWindow w(4);
    for (double v : {5.0, 1.0, 3.0, 2.0, 4.0})
        w.add(v); // 5.0 falls out of the window
    const SampleStats s = w.stats();
    CHECK(s.count == 4);
    CHECK(s.last == 4.0);
    CHECK(s.mean == doctest::Approx(2.5));
    CHECK(s.median == doctest::Approx(2.5));
    CHECK(s.p95 == 4.0);
    CHECK(s.max == 4.0);
}

TEST_CASE("profiler: budget checks trip exactly past the boundary") {
    auto device = nullDevice();
    // Frame budget 10 us; GI budget 4 us.
    FrameProfiler profiler(*device, tinyProfile(0.010, 0.004));
    frame(*device, profiler, 6, 4); // 10 us frame, 4 us GI: at the budgets, not over
    frame(*device, profiler, 7, 4); // 11 us frame: over
    frame(*device, profiler, 5, 5); // 10 us frame, 5 us GI: GI over
    device->waitIdle();
    frame(*device, profiler, 1, 1); // resolves the three above
    REQUIRE(profiler.framesChecked() >= 3);
    std::vector<FrameBudgetCheck> checks;
    profiler.forEachFrame([&](const FrameProfiler::FrameRecord& r) {
        if (r.checked) checks.push_back(r.check);
    });
    REQUIRE(checks.size() >= 3);
    CHECK(checks[0].frameMs == doctest::Approx(0.010));
    CHECK_FALSE(checks[0].frameOverBudget);
    CHECK_FALSE(checks[0].giOverBudget);
    CHECK(checks[1].frameOverBudget);
    CHECK_FALSE(checks[1].giOverBudget);
    CHECK_FALSE(checks[2].frameOverBudget);
    CHECK(checks[2].giOverBudget);
    CHECK(profiler.framesOverBudget() == 2);
}

// On x360 and ps3 the GI check holds the predicted console time to the GI budget: the pass table
// said "ok" for a gi row whose prediction was twice the budget, on frames counted over it.
TEST_CASE("profiler: on a console profile a GI pass predicted over the GI budget is OVER in the report") {
    auto device = nullDevice();
    platforms::PlatformProfile x360 = platforms::loadPlatformProfile("x360");
    x360.giBudgetMs = 0.5; // the propagate pass's work is 1 ms on Xbox 360; measured, microseconds
    FrameProfiler profiler(*device, x360);
    for (int i = 0; i < 6; ++i)
        frame(*device, profiler, 1, 1);
    profiler.collectPending();
    CHECK(profiler.framesOverBudget() == profiler.framesChecked());
    const std::string md = profileSummaryMarkdown(profiler);
    const size_t row = md.find("gi/propagate |");
    REQUIRE(row != std::string::npos);
    const std::string line = md.substr(row, md.find('\n', row) - row);
    CHECK(line.find("(predicted x360: 200.0%)") != std::string::npos);
    CHECK(line.find("**OVER**") != std::string::npos);
    CHECK(profileSummaryText(profiler).find("OVER") != std::string::npos);
    CHECK(profileSummaryCsv(profiler).find(",200.00,") != std::string::npos); // commands follow
    CHECK(profileTraceJson(profiler).find("\"gi_predicted_ms\":1.0") != std::string::npos);
    // Off the consoles nothing is predicted against the budget.
    auto pcDevice = nullDevice();
    FrameProfiler pc(*pcDevice, tinyProfile(100, 0.5));
    for (int i = 0; i < 6; ++i)
        frame(*pcDevice, pc, 1, 1);
    CHECK(profileSummaryMarkdown(pc).find("predicted x360:") == std::string::npos);
    CHECK(profileTraceJson(pc).find("gi_predicted_ms") == std::string::npos);
}

// 6 frames of two top-level GI passes, gi and gi.rebuild, each 0.3 ms of ALU work on Xbox 360.
static void twoGiPassFrames(rhi::Device& device, FrameProfiler& profiler) {
    for (int i = 0; i < 6; ++i) {
        rhi::CommandList& cmd = device.beginFrame();
        profiler.beginFrame(cmd);
        for (const char* name : {"gi", "gi.rebuild"}) {
            auto s = profiler.scope(name, &cmd);
            WorkCounts w;
            w.aluOps = 72'000'000;
            profiler.setWork(w);
        }
        profiler.endFrame(cmd);
        device.endFrame();
    }
    profiler.collectPending();
}

// gi.rebuild runs inside render.lighting's pass: its own row has no time of its own, and said "cpu"
// as if it had been timed there.
TEST_CASE("profiler: a pass measured inside another's time names that pass as its timing") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    for (int i = 0; i < 3; ++i) {
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        { auto s = profiler.scope("render.lighting", &cmd); }
        {
            auto s = profiler.scope("gi.rebuild");
            profiler.setTimedIn("render.lighting");
        }
        profiler.endFrame(cmd);
        device->endFrame();
    }
    profiler.collectPending();
    const std::string md = profileSummaryMarkdown(profiler), csv = profileSummaryCsv(profiler);
    INFO(md);
    CHECK(md.find("| gi.rebuild | in render.lighting |") != std::string::npos);
    CHECK(csv.find("gi.rebuild,0,in render.lighting,") != std::string::npos);
    CHECK(md.find("| render.lighting | in ") == std::string::npos);
    CHECK_THROWS_AS(profiler.setTimedIn("render.lighting"), std::logic_error); // no scope open
}

// Two GI passes each within the budget, together over it: every row said ok while the header
// counted every frame over budget. And a custom profile's [throughput] was read, then ignored: the
// prediction used the built-in x360's, and only a profile named x360 or ps3 was held to it.
TEST_CASE("profiler: the GI total is held to the budget, on the active profile's own throughput") {
    platforms::PlatformProfile slow = platforms::loadPlatformProfile("x360");
    slow.name = "slow";
    slow.throughput.aluGflops /= 10; // the same work takes 10x as long
    slow.giBudgetMs = 12.0;
    for (const bool predicted : {true, false}) {
        CAPTURE(predicted);
        slow.giTimePredicted = predicted;
        auto device = nullDevice();
        FrameProfiler profiler(*device, slow);
        twoGiPassFrames(*device, profiler);
        const FrameBudgetCheck& check = profiler.lastBudgetCheck();
        CHECK(check.giPredictedX360Ms == doctest::Approx(0.6));
        CHECK(check.giPredictedMs == doctest::Approx(6.0));
        CHECK(check.giBudgetedMs == doctest::Approx(predicted ? 6.0 : check.giMs));
        CHECK_FALSE(check.giPredictedOverBudget); // 6 of 12 ms
        const std::string md = profileSummaryMarkdown(profiler);
        INFO(md);
        CHECK((md.find("(predicted slow: 25.0%)") != std::string::npos) == predicted);
        const std::string csv = profileSummaryCsv(profiler);
        // Over the 5 steady-state frames: the first ran both passes for the first time (warm-up).
        CHECK(csv.find(predicted ? "gi,5,0.0" : "gi,5,") != std::string::npos);
        CHECK(csv.find(predicted ? ",6.0000,12.0000,50.00,\"predicted slow\"\n" : ",\"measured\"\n") !=
              std::string::npos);
        // Each pass 40% of a 7.5 ms budget, together 80%; at 4.5 ms each is 67%, together 133%.
        for (const double budget : {7.5, 4.5}) {
            CAPTURE(budget);
            slow.giBudgetMs = budget;
            auto d = nullDevice();
            FrameProfiler p(*d, slow);
            twoGiPassFrames(*d, p);
            const std::string report = profileSummaryMarkdown(p);
            const size_t total = report.find("| **GI total**");
            REQUIRE(total != std::string::npos);
            const std::string line = report.substr(total, report.find('\n', total) - total);
            INFO(line);
            const size_t gi = report.find("| gi |");
            REQUIRE(gi != std::string::npos);
            CHECK(report.substr(gi, report.find('\n', gi) - gi).find("| ok |") != std::string::npos);
            CHECK((line.find("**OVER**") != std::string::npos) == (predicted && budget == 4.5));
            CHECK((p.framesOverGiBudget() > 0) == (predicted && budget == 4.5));
            CHECK(profileSummaryText(p).find(
                      predicted ? "the predicted slow time the GI budget holds): median 6.00 ms"
                                : "the measured time the GI budget holds)") != std::string::npos);
        }
        slow.giBudgetMs = 12.0;
    }
    // A tiny budget is printed with the digits it needs, not as "0.00 ms".
    auto device = nullDevice();
    FrameProfiler tiny(*device, tinyProfile(0.001, 0.0005));
    CHECK(profileSummaryText(tiny).find("frame budget 0.0010 ms, GI 0.0005 ms") != std::string::npos);
}

TEST_CASE("profiler: a frame's memory counter includes what the frame made") {
    // The renderer makes its targets and the GI its volumes lazily, inside their first frame.
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    frame(*device, profiler, 1, 1);
    rhi::CommandList& cmd = device->beginFrame();
    profiler.beginFrame(cmd);
    rhi::BufferDesc desc;
    desc.size = 3 << 20;
    desc.usage = rhi::kBufferStorage;
    desc.category = "gi.lpv";
    const rhi::BufferHandle made = device->createBuffer(desc);
    profiler.endFrame(cmd);
    device->endFrame();
    const auto trace = nlohmann::json::parse(profileTraceJson(profiler));
    std::vector<uint64_t> gi;
    for (const auto& e : trace.at("traceEvents"))
        if (e.at("ph") == "C" && e.at("name") == "memory") gi.push_back(e.at("args").at("gi_bytes"));
    REQUIRE(gi.size() == 2);
    CHECK(gi[0] == 0);
    CHECK(gi[1] >= desc.size);
    device->destroy(made);
}

TEST_CASE("profiler: the trace is valid JSON with CPU and GPU tracks, counters and every pass") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    for (int i = 0; i < 5; ++i)
        frame(*device, profiler, 2, 2);
    const auto trace = nlohmann::json::parse(profileTraceJson(profiler));
    std::set<std::string> threads, names, counters;
    std::set<int> tids;
    for (const auto& e : trace.at("traceEvents")) {
        if (e.at("ph") == "M" && e.at("name") == "thread_name") threads.insert(e.at("args").at("name"));
        if (e.at("ph") == "X") {
            names.insert(e.at("name"));
            tids.insert(e.at("tid").get<int>());
            CHECK(e.at("dur").get<double>() >= 0.0);
        }
        if (e.at("ph") == "C") counters.insert(e.at("name"));
    }
    CHECK(threads == std::set<std::string>{"CPU", "GPU (simulated)"});
    CHECK(tids == std::set<int>{1, 2});
    CHECK(names.count("render/gbuffer") == 1);
    CHECK(names.count("gi/propagate") == 1);
    CHECK(counters == std::set<std::string>{"commands", "memory", "budget"});
    // The other outputs carry the same passes and the timing source.
    const std::string md = profileSummaryMarkdown(profiler);
    CHECK(md.find("gi/propagate") != std::string::npos);
    CHECK(md.find("`simulated`") != std::string::npos);
    CHECK(profileSummaryCsv(profiler).find("render/gbuffer,1,simulated,") != std::string::npos);
    const std::string svg = profileChartSvg(profiler);
    CHECK(svg.find("<svg") == 0);
    CHECK(svg.find("frame budget") != std::string::npos);
}

TEST_CASE("profiler: cost model predictions match hand-computed values") {
    const auto x360 = platforms::loadPlatformProfile("x360").throughput;
    const auto ps3 = platforms::loadPlatformProfile("ps3").throughput;
    WorkCounts w;
    w.aluOps = 480'000'000;    // x360: 480e6 / 240e9 = 2 ms
    w.texelsRead = 8'000'000;  // x360: 8e6 / 8e9 = 1 ms
    w.bytesMoved = 11'200'000; // x360: 11.2e6 / 22.4e9 = 0.5 ms
    const CostPrediction p = predictCost(w, x360);
    CHECK(p.aluMs == doctest::Approx(2.0));
    CHECK(p.textureMs == doctest::Approx(1.0));
    CHECK(p.memoryMs == doctest::Approx(0.5));
    CHECK(p.ms == doctest::Approx(2.0));
    CHECK(std::string(p.bottleneck) == "alu");
    const CostPrediction q = predictCost(w, ps3);
    CHECK(q.aluMs == doctest::Approx(480e6 / 211.2e9 * 1e3));
    CHECK(q.textureMs == doctest::Approx(8e6 / 13.2e9 * 1e3));
    WorkCounts fill;
    fill.texelsWritten = 4'400'000; // ps3: 4.4e6 / 4.4e9 = 1 ms
    CHECK(predictCost(fill, ps3).ms == doctest::Approx(1.0));
    CHECK(std::string(predictCost(fill, ps3).bottleneck) == "fill");
}

TEST_CASE("profiler: passes over their budget are flagged in the summary") {
    auto device = nullDevice();
    FrameProfiler generous(*device, tinyProfile(100, 100));
    FrameProfiler tight(*device, tinyProfile(0.002, 0.001)); // 2 us frame, 1 us GI
    for (FrameProfiler* p : {&generous, &tight})
        for (int i = 0; i < 4; ++i)
            frame(*device, *p, 3, 2);
    CHECK(profileSummaryMarkdown(generous).find("**OVER**") == std::string::npos);
    const std::string md = profileSummaryMarkdown(tight);
    // gi/propagate takes 2 us, twice the GI budget; render/gbuffer 3 us, over the frame budget.
    const auto rowOf = [&](const std::string& pass) {
        return md.substr(md.find(pass), md.find('\n', md.find(pass)) - md.find(pass));
    };
    CHECK(rowOf("gi/propagate").find("**OVER**") != std::string::npos);
    CHECK(rowOf("render/gbuffer").find("**OVER**") != std::string::npos);
}

// A run longer than the trace's frames lost its early notes (adapt's steps) from the trace and the
// chart, though the summaries kept them.
TEST_CASE("profiler: notes of frames before the trace's are kept in the trace and counted in the chart") {
    auto device = nullDevice();
    ProfilerOptions options;
    options.traceFrames = 8;
    FrameProfiler profiler(*device, tinyProfile(100, 100), options);
    profiler.note("GI budget changes", "an early step");
    for (int i = 0; i < 20; ++i)
        frame(*device, profiler, 1, 1);
    profiler.collectPending();
    const auto trace = nlohmann::json::parse(profileTraceJson(profiler));
    int early = 0;
    for (const auto& e : trace["traceEvents"])
        if (e.value("name", "") == "an early step") {
            ++early;
            CHECK(e["args"]["before_trace"] == true);
            CHECK(e["ts"].get<double>() == 0.0);
        }
    CHECK(early == 1);
    CHECK(profileChartSvg(profiler).find("notes on 1 earlier frames: summary.md") != std::string::npos);
}

TEST_CASE("profiler: notes belong to their frame and reach every report") {
    auto device = nullDevice();
    ProfilerOptions options;
    options.maxNotes = 4;
    FrameProfiler profiler(*device, tinyProfile(100, 100), options);
    frame(*device, profiler, 1, 1);
    CHECK(profileSummaryMarkdown(profiler).find("| frame | note |") ==
          std::string::npos); // no notes, no section

    profiler.note("GI budget changes", "made between frames"); // goes to the next frame
    uint64_t noted = 0;
    profiler.forEachNote([&](const FrameProfiler::Note&) { ++noted; });
    CHECK(noted == 0); // not yet placed in a frame
    rhi::CommandList& cmd = device->beginFrame();
    profiler.beginFrame(cmd);
    const uint64_t second = device->frameIndex();
    profiler.note("other topic", std::string(500, 'x')); // cut to fit
    profiler.endFrame(cmd);
    device->endFrame();

    std::vector<std::tuple<uint64_t, std::string, std::string>> notes;
    profiler.forEachNote([&](const FrameProfiler::Note& n) {
        notes.emplace_back(n.frame, std::string(n.topic()), std::string(n.text()));
    });
    REQUIRE(notes.size() == 2);
    CHECK(notes[0] ==
          std::tuple(second, std::string("GI budget changes"), std::string("made between frames")));
    CHECK(std::get<0>(notes[1]) == second);
    CHECK(std::get<2>(notes[1]) == std::string(FrameProfiler::Note::kTextBytes - 1, 'x'));

    const std::string md = profileSummaryMarkdown(profiler);
    CHECK(md.find("## GI budget changes\n\n| frame | note |\n|---|---|\n| " + std::to_string(second) +
                  " | made between frames |") != std::string::npos);
    CHECK(md.find("## other topic") != std::string::npos);
    CHECK(profileSummaryText(profiler).find("GI budget changes:\n  frame " + std::to_string(second) +
                                            ": made between frames") != std::string::npos);
    CHECK(profileSummaryCsv(profiler).find("\nframe,topic,note\n" + std::to_string(second) +
                                           ",\"GI budget changes\",\"made between frames\"") !=
          std::string::npos);
    const auto trace = nlohmann::json::parse(profileTraceJson(profiler));
    int instants = 0;
    for (const auto& e : trace.at("traceEvents"))
        if (e.at("ph") == "i") {
            ++instants;
            CHECK(e.at("args").at("frame").get<uint64_t>() == second);
        }
    CHECK(instants == 2);

    // The newest maxNotes are kept; the report says how many gave way.
    for (int i = 0; i < 5; ++i) {
        rhi::CommandList& c = device->beginFrame();
        profiler.beginFrame(c);
        profiler.note("GI budget changes", "note " + std::to_string(i));
        profiler.endFrame(c);
        device->endFrame();
    }
    std::vector<std::string> kept;
    profiler.forEachNote([&](const FrameProfiler::Note& n) { kept.emplace_back(n.text()); });
    CHECK(kept == std::vector<std::string>{"note 1", "note 2", "note 3", "note 4"});
    CHECK(profiler.notesDropped() == 3);
    CHECK(profileSummaryText(profiler).find("(3 older notes dropped)") != std::string::npos);
}

// A note about a frame that has ended (a result read back later, or at the end of a run) goes
// under that frame and is reported at once; notes waiting for the next frame stay waiting.
TEST_CASE("profiler: a note about an ended frame is reported under that frame") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    frame(*device, profiler, 1, 1);
    const uint64_t ended = device->frameIndex();
    frame(*device, profiler, 1, 1);
    profiler.note("next", "waits for the next frame");
    profiler.note("GI RGBA8 clipping", "read back late", ended);
    std::vector<std::pair<uint64_t, std::string>> notes;
    profiler.forEachNote(
        [&](const FrameProfiler::Note& n) { notes.emplace_back(n.frame, std::string(n.text())); });
    REQUIRE(notes.size() == 1);
    CHECK(notes[0] == std::pair(ended, std::string("read back late")));
    CHECK(profileSummaryMarkdown(profiler).find("| " + std::to_string(ended) + " | read back late |") !=
          std::string::npos);

    frame(*device, profiler, 1, 1);
    const uint64_t next = device->frameIndex();
    notes.clear();
    profiler.forEachNote(
        [&](const FrameProfiler::Note& n) { notes.emplace_back(n.frame, std::string(n.text())); });
    REQUIRE(notes.size() == 2);
    CHECK(notes[1] == std::pair(next, std::string("waits for the next frame")));
}

// A pass's predicted console time in the report is its passes of the last frame that ran it, each
// predicted and added, as the budget check adds them: the gi row used to predict the summed work
// of every pass that had ever run under it (one roofline over the sum, less than the sum of the
// passes'), and counted passes that had stopped running.
TEST_CASE("profiler: a parent's predicted time adds its passes of the last frame that ran it") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, platforms::loadPlatformProfile("x360"));
    WorkCounts alu, fetches;
    alu.aluOps = 200'000'000;
    fetches.texelsRead = 20'000'000;
    const auto run = [&](bool stoppedPassToo) {
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        {
            auto gi = profiler.scope("gi");
            {
                auto a = profiler.scope("math");
                profiler.setWork(alu);
            }
            {
                auto b = profiler.scope("fetch");
                profiler.setWork(fetches);
            }
            if (stoppedPassToo) {
                auto c = profiler.scope("stopped");
                profiler.setWork(alu);
            }
        }
        profiler.endFrame(cmd);
        device->endFrame();
    };
    run(true);
    run(false);
    profiler.collectPending();
    const double math = predictCost(alu, profiler.x360().throughput).ms;
    const double fetch = predictCost(fetches, profiler.x360().throughput).ms;
    WorkCounts both = alu;
    both += fetches;
    REQUIRE(predictCost(both, profiler.x360().throughput).ms < 0.95 * (math + fetch)); // the two differ
    // "pass,depth,timing_source,...,predicted_x360_ms,..." in the CSV: the 10th column.
    const std::string csv = profileSummaryCsv(profiler);
    const auto predictedOf = [&](const std::string& path) {
        const size_t at = csv.find("\n" + path + ",");
        REQUIRE(at != std::string::npos);
        size_t field = at + 1;
        for (int i = 0; i < 9; ++i)
            field = csv.find(',', field) + 1;
        return std::stod(csv.substr(field));
    };
    CHECK(predictedOf("gi") == doctest::Approx(math + fetch).epsilon(1e-3));
    CHECK(predictedOf("gi/math") == doctest::Approx(math).epsilon(1e-3));
    // The stopped pass keeps its own last run, but its parent no longer counts it.
    CHECK(predictedOf("gi/stopped") == doctest::Approx(math).epsilon(1e-3));
}

TEST_CASE("profiler: the predicted GI time adds up its passes, and names the frame it is of") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, platforms::loadPlatformProfile("x360"));
    // Two passes bound by different units: 1 ms of ALU, then 1 ms of texture fetches on Xenos.
    // Passes run one after the other, so 2 ms; a roofline of their summed work would say 1 ms.
    const auto giFrame = [&] {
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        {
            auto gi = profiler.scope("gi", &cmd);
            {
                auto a = profiler.scope("propagate", &cmd);
                WorkCounts w;
                w.aluOps = 240'000'000;
                profiler.setWork(w);
            }
            auto b = profiler.scope("lookup", &cmd);
            WorkCounts w;
            w.texelsRead = 8'000'000;
            profiler.setWork(w);
        }
        profiler.endFrame(cmd);
        device->endFrame();
        return device->frameIndex();
    };
    const uint64_t first = giFrame();
    for (int i = 0; i < 3; ++i)
        giFrame();
    REQUIRE(profiler.framesChecked() >= 1);
    const FrameBudgetCheck& check = profiler.lastBudgetCheck();
    CHECK(check.frame >= first);
    CHECK(check.frame < device->frameIndex());
    CHECK(check.giPredictedX360Ms == doctest::Approx(2.0));
    CHECK(check.giBudgetedMs == doctest::Approx(2.0)); // x360: held to the predicted time
    CHECK(check.giPredictedOverBudget == false);       // 2 ms of a 3.3 ms budget
}

// The report is of the steady state: a frame that made or freed resources (before it began, as a
// GI rebuild does, or in it) or ran a pass for the first time (compiling its pipelines) is marked
// warm-up and left out of the statistics, and the report says how many.
TEST_CASE("profiler: warm-up frames are marked and left out of the report's statistics") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    frame(*device, profiler, 50, 2); // 1: every pass runs for the first time
    frame(*device, profiler, 3, 2);  // 2: steady
    const rhi::BufferHandle buffer = device->createBuffer({4096, rhi::kBufferStorage});
    frame(*device, profiler, 50, 2); // 3: a resource made before it began
    device->destroy(buffer);
    frame(*device, profiler, 50, 2); // 4: and freed
    frame(*device, profiler, 3, 2);  // 5: steady
    profiler.collectPending();
    std::vector<uint8_t> warmUp;
    profiler.forEachFrame([&](const FrameProfiler::FrameRecord& r) { warmUp.push_back(r.warmUp); });
    CHECK(warmUp ==
          std::vector<uint8_t>{kWarmUpFirstRunOfPass, 0, kWarmUpMadeResources, kWarmUpMadeResources, 0});
    CHECK(profiler.warmUp().frames == 3);
    CHECK(profiler.warmUp().madeResources == 2);
    CHECK(profiler.warmUp().firstRunOfPass == 1);
    CHECK(profiler.warmUp().checked == 3);
    // The live window holds every frame (median of 50, 3, 50, 50, 3 dispatches); the report the
    // two steady ones (3 dispatches, 1 us each in the null device).
    CHECK(profiler.scopes()[1].gpuMs.stats().median == doctest::Approx(0.050));
    const std::string text = profileSummaryText(profiler);
    INFO(text);
    CHECK(text.find("Steady state: 3 warm-up frames left out of the statistics (frames 1, 3 and 4)") !=
          std::string::npos);
    CHECK(text.find("frames checked 5, 3 of them warm-up; over budget 0 of the 2 steady-state frames") !=
          std::string::npos);
    const size_t row = text.find("\n  gbuffer ");
    REQUIRE(row != std::string::npos);
    CHECK(text.substr(row, 60).find("0.003") != std::string::npos);
    CHECK(text.substr(row, 60).find("0.050") == std::string::npos);
    CHECK(profileSummaryCsv(profiler).find("\nreached,2,3,2,1\n") != std::string::npos);
    const std::string brief = profileShortSummary(profiler, "out/summary.md");
    CHECK(brief.find("2 steady-state frames (3 warm-up frames left out") != std::string::npos);
    CHECK(brief.find("The full report: out/summary.md") != std::string::npos);
}

// One frame is all warm-up: no steady state, said, and its figures are that frame's.
TEST_CASE("profiler: a run of warm-up frames only says it has no steady state") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    frame(*device, profiler, 3, 2);
    profiler.collectPending();
    const std::string text = profileSummaryText(profiler);
    INFO(text);
    CHECK(text.find("Steady state: not reached") != std::string::npos);
    CHECK(text.find("gpu median 0.005 ms") != std::string::npos);
    CHECK(profileShortSummary(profiler, "").find("no steady state yet") != std::string::npos);
}

TEST_CASE("profiler: commands per pass and per frame, and the GI's dependent-pass chain, in the reports") {
    auto device = nullDevice();
    FrameProfiler profiler(*device, tinyProfile(100, 100));
    for (int i = 0; i < 3; ++i)
        frame(*device, profiler, 2, 3);
    // The null device counts a barrier after each dispatch, so each dispatch is a stage of its own.
    REQUIRE(profiler.scopes().size() == 4);
    CHECK(profiler.scopes()[1].commands == rhi::CommandCounts{2, 0, 0, 2, 2}); // render/gbuffer
    CHECK(profiler.scopes()[0].commands == profiler.scopes()[1].commands);     // render: nested included
    CHECK(profiler.scopes()[2].commands == rhi::CommandCounts{3, 0, 0, 3, 3}); // gi
    CHECK(device->frameCounters() == rhi::CommandCounts{5, 0, 0, 5, 5});

    const std::string csv = profileSummaryCsv(profiler);
    CHECK(csv.find(",3,0,0,3,3\n") != std::string::npos);
    CHECK(csv.find("commands,frame,dispatches,draws,draws_indexed,barriers,stages\nframe,3,5,0,0,5,5\ngi,3,3,"
                   "0,0,3,3\n") != std::string::npos);
    const std::string md = profileSummaryMarkdown(profiler);
    CHECK(md.find("GI dependent-pass chain: 3 stages") != std::string::npos);
    CHECK(md.find("| 2 | 0 | 2 | 2 |") != std::string::npos); // render/gbuffer's columns
    const auto trace = nlohmann::json::parse(profileTraceJson(profiler));
    int withArgs = 0;
    for (const auto& e : trace["traceEvents"])
        if (e.value("name", "") == "gi/propagate" && e.value("tid", 0) == 1) {
            CHECK(e["args"]["dispatches"] == 3);
            CHECK(e["args"]["barriers"] == 3);
            ++withArgs;
        }
    CHECK(withArgs == 3);
}
