// The budget scheduler as a game would run it: frames on the null device, each GI pass a profiler
// scope with its work counts, the scheduler fed the profiler's predicted Xbox 360 GI time (which
// arrives frames late, as GPU results do), and its changes noted in the profiler's report.
#include "AdaptedLpv.h"
#include "ConsoleGiCost.h"

#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfileReport.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/Renderer.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/GiScheduler.h"
#include "gi/LightPropagationVolume.h"
#include "gi/VplGather.h"
#include "gi/VplWindows.h"
#include "gi/adapter/EngineFrame.h"
#include "rhi/Device.h"

#include "../support/TestDevice.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::gi;

namespace {

using test::AdaptedLpv;
using test::nullDevice;

// One frame's GI as scopes: the halves of every cascade update due this frame, then the lookup.
void recordGi(engine::FrameProfiler& profiler, rhi::CommandList& cmd, const test::ConsoleGiCost& cost,
              const GiSchedule& s) {
    static const char* kCascades[] = {"cascade0", "cascade1", "cascade2", "cascade3"};
    static const char* kLightPasses[] = {"rsm", "vpl"};
    static const char* kVolumePasses[] = {"inject", "propagate"};
    auto gi = profiler.scope("gi", &cmd);
    const auto record = [&](const char* const* names, const auto& passes) {
        for (size_t p = 0; p < passes.size(); ++p) {
            auto pass = profiler.scope(names[p], &cmd);
            profiler.setWork(passes[p]);
            cmd.dispatch(1);
        }
    };
    for (uint32_t c = 0; c < s.load.cascades; ++c) {
        const uint32_t halves = s.cascadeWork(c);
        if (!halves) continue;
        auto cascade = profiler.scope(kCascades[c], &cmd);
        if (halves & kCascadeLight) record(kLightPasses, cost.lightPasses(s.load));
        if (halves & kCascadeVolume) record(kVolumePasses, cost.volumePasses(s.load));
    }
    auto lookup = profiler.scope("lookup", &cmd);
    profiler.setWork(cost.lookupPass(s.load));
}

} // namespace

TEST_CASE("gi budget report: the profiler's report names each change, its frame and its reason") {
    GiLoad configured;
    const test::ConsoleGiCost cost = test::x360Cascades(configured);
    auto device = nullDevice();
    const auto x360 = platforms::loadPlatformProfile("x360");
    engine::FrameProfiler profiler(*device, x360);
    GiBudgetScheduler scheduler;
    // The x360's 3 MiB holds one cascade, not three: this test is about time, the null device
    // allocates no GI memory, so the memory budget holds.
    const GiBudget budget = giBudgetOf(x360);

    std::vector<std::pair<uint64_t, std::string>> noted;
    const GiSchedule* s = nullptr;
    for (int i = 0; i < 150; ++i) {
        const uint64_t frame = device->frameIndex() + 1;
        s = &scheduler.schedule(frame, giFrameCost(profiler), budget, configured, GiBudgetPolicy::Adapt);
        for (const GiChange& c : s->changes()) {
            profiler.note(kGiBudgetNoteTopic, c.text()); // before beginFrame: goes to `frame`
            noted.emplace_back(frame, std::string(c.text()));
        }
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        recordGi(profiler, cmd, cost, *s);
        profiler.endFrame(cmd);
        device->endFrame();
    }
    device->waitIdle();

    // The profiler's own check of the newest frames: the predicted console GI time is in budget.
    const engine::FrameBudgetCheck& check = profiler.lastBudgetCheck();
    MESSAGE("last checked frame " << check.frame << ": predicted x360 GI " << check.giPredictedX360Ms
                                  << " ms");
    CHECK(check.giBudgetedMs == check.giPredictedX360Ms);
    double latePeak = 0;
    uint64_t checkedLate = 0;
    profiler.forEachFrame([&](const engine::FrameProfiler::FrameRecord& r) {
        if (r.checked && r.frame > 100) {
            latePeak = std::max(latePeak, r.check.giPredictedX360Ms);
            ++checkedLate;
        }
    });
    REQUIRE(checkedLate > 20);
    CHECK(latePeak <= x360.giBudgetMs);
    CHECK_FALSE(profiler.lastBudgetCheck().giPredictedOverBudget);
    // And the configured load was over it, so the scheduler had something to do.
    CHECK(cost.peakMs(configured) > x360.giBudgetMs);

    REQUIRE(noted.size() >= 2);
    CHECK(noted[0].second.find("gi.coarse_update_interval=2 (was 1): frame ") == 0);
    // Every 4 frames gives each of the 2 coarse cascades two frames of its own: its update splits.
    CHECK(noted[1].second.find("gi.coarse_update_interval=4 (was 2): frame ") == 0);

    // A note quotes the GI time of the frame it names, which is earlier than the frame it is
    // noted under (GPU times arrive frames late; a cycle is judged by its worst frame): it said
    // "GI 4.2 ms" under frame 3 for frame 1's time.
    for (const auto& [frame, note] : noted) {
        INFO(note);
        unsigned long long judged = 0;
        double ms = 0;
        const size_t at = note.find(": frame ");
        REQUIRE(at != std::string::npos);
        REQUIRE(std::sscanf(note.c_str() + at, ": frame %llu's GI %lf ms", &judged, &ms) == 2);
        CHECK(judged < frame);
        bool found = false;
        profiler.forEachFrame([&](const engine::FrameProfiler::FrameRecord& r) {
            if (r.frame != judged) return;
            found = true;
            CHECK(std::fabs(r.check.giBudgetedMs - ms) <= 0.0051); // printed with 2 decimals
        });
        CHECK(found); // the trace keeps 1200 frames, these 150 among them
    }

    // Each note is in the profiler under its frame ...
    std::vector<std::pair<uint64_t, std::string>> kept;
    profiler.forEachNote([&](const engine::FrameProfiler::Note& n) {
        CHECK(n.topic() == kGiBudgetNoteTopic);
        kept.emplace_back(n.frame, std::string(n.text()));
    });
    CHECK(kept == noted);
    // ... in the summaries ...
    const std::string md = engine::profileSummaryMarkdown(profiler);
    const size_t section = md.find("## GI budget changes");
    REQUIRE(section != std::string::npos);
    const std::string text = engine::profileSummaryText(profiler);
    const std::string csv = engine::profileSummaryCsv(profiler);
    for (const auto& [frame, note] : noted) {
        INFO(note);
        CHECK(md.find("| " + std::to_string(frame) + " | " + note + " |", section) != std::string::npos);
        CHECK(text.find("frame " + std::to_string(frame) + ": " + note) != std::string::npos);
        CHECK(csv.find(std::to_string(frame) + ",\"GI budget changes\",\"" + note + "\"") !=
              std::string::npos);
    }
    // ... and in the trace, as instant events carrying the frame.
    const auto trace = nlohmann::json::parse(engine::profileTraceJson(profiler));
    std::vector<std::pair<uint64_t, std::string>> events;
    for (const auto& e : trace.at("traceEvents"))
        if (e.at("ph") == "i") {
            CHECK(e.at("cat") == "GI budget changes");
            events.emplace_back(e.at("args").at("frame").get<uint64_t>(), e.at("name").get<std::string>());
        }
    CHECK(events == noted);
    CHECK(engine::profileChartSvg(profiler).find("blue marks: notes") != std::string::npos);
}

TEST_CASE("gi budget: the LPV under adapt on the x360 profile brings its predicted GI time under budget") {
    // 44 iterations: about 3.8 ms predicted on the Xbox 360.
    AdaptedLpv run(platforms::loadPlatformProfile("x360"), 44);
    std::optional<GiFrameCost> first, last;
    for (int f = 0; f < 60; ++f) {
        const auto cost = run.frame();
        if (cost && !first) first = cost;
        if (cost) last = cost;
    }
    REQUIRE(first);
    REQUIRE(last);
    MESSAGE("predicted x360 GI: first checked frame " << first->ms << " ms, last " << last->ms << " ms; "
                                                      << run.lpv.schedule().load.iterations << " iterations");
    CHECK(first->ms > run.profile.giBudgetMs);
    CHECK(last->ms <= run.profile.giBudgetMs);
    CHECK(run.lpv.schedule().load.iterations < 44);
    const std::string report = engine::profileSummaryMarkdown(run.profiler);
    CHECK(report.find("gi.iterations=33 (was 44): frame ") != std::string::npos);
}

// gi.gather=on on the Xbox 360 (auto leaves it off on the console profiles; 24^3 cells, so that
// its first bounce kept apart fits the 3 MiB): adapt's first step turns it off, without making
// the volumes again, and the frame fits.
TEST_CASE("gi budget: adapt turns gi.gather off on the x360 profile, keeping the cascades") {
    AdaptedLpv run(platforms::loadPlatformProfile("x360"),
                   {"gi.enabled=true", "gi.sh_format=rgba8", "gi.rsm_size=128", "gi.vpl_count=1024",
                    "gi.cascades=1", "gi.budget_policy=adapt", "gi.iterations=8", "gi.gather=on",
                    "gi.grid_size=24"},
                   engine::buildCornellBox(), 1280, 720);
    std::optional<GiFrameCost> first, last;
    rhi::TextureHandle result; // the finest cascade's result while the gather ran
    for (int f = 0; f < 40; ++f) {
        const auto cost = run.frame();
        REQUIRE_MESSAGE(run.lastUpdate.accepted, run.lastUpdate.message());
        if (cost && !first) {
            first = cost;
            result = run.lpv.volumes()->accumulated()[0];
        }
        if (cost) last = cost;
    }
    REQUIRE(first);
    MESSAGE("predicted x360 GI with the gather " << first->ms << " ms, last " << last->ms << " ms");
    CHECK(first->ms > run.profile.giBudgetMs);
    CHECK(last->ms <= run.profile.giBudgetMs);
    CHECK_FALSE(run.lpv.settings().gather);
    CHECK(run.lpv.schedule().load.iterations == 8);
    const std::string report = engine::profileSummaryMarkdown(run.profiler);
    CHECK(report.find("gi.gather=off (was on): frame ") != std::string::npos);
    // Turning it off kept the volumes: the same result texture.
    CHECK(run.lpv.volumes()->accumulated()[0] == result);
}

// A change the budget check refuses (the GI goes on with the settings that ran) leaves the
// scheduler as it was: its steps used to be dropped by the refused configuration (with a note for
// a change that never took effect), and the restored one started again from the configured load.
TEST_CASE("gi budget: a change the budget check refuses leaves adapt's steps in place") {
    AdaptedLpv run(platforms::loadPlatformProfile("x360"), 44);
    for (int f = 0; f < 60; ++f)
        run.frame();
    const gi::GiSchedule before = run.lpv.schedule();
    REQUIRE(before.stepsInEffect > 0);
    uint64_t notesBefore = 0;
    run.profiler.forEachNote([&](const engine::FrameProfiler::Note&) { ++notesBefore; });

    // A change of the scheduler's load (the cascades) that does not fit the Xbox 360's 3 MiB: the
    // frame runs the configuration that ran before.
    run.config.applyOverride("gi.cascades=3", "console");
    run.frame();
    CHECK(!run.lastUpdate.accepted);
    CHECK(run.lastUpdate.reason.find("over platform 'x360' GI memory budget") != std::string::npos);
    CHECK(run.lpv.settings().cascades == 1);
    run.config.applyOverride("gi.cascades=1", "restored");
    run.frame();
    CHECK(run.lastUpdate.accepted);
    CHECK(run.lpv.schedule().stepsInEffect == before.stepsInEffect);
    CHECK(run.lpv.schedule().load == before.load);
    uint64_t notesAfter = 0;
    bool restarted = false;
    run.profiler.forEachNote([&](const engine::FrameProfiler::Note& n) {
        ++notesAfter;
        restarted = restarted || n.text().find("configured load again") != std::string_view::npos;
    });
    CHECK_FALSE(restarted);
    CHECK(notesAfter == notesBefore);
}

TEST_CASE("gi budget: past the RSM, adapt makes the renderer look up fewer pixels") {
    // Under a budget no knob reaches, the ladder ends at gi.resolution, and the renderer's indirect
    // targets follow it.
    platforms::PlatformProfile tight = platforms::loadPlatformProfile("x360");
    tight.giBudgetMs = 0.5;
    AdaptedLpv run(tight, 8);
    for (int f = 0; f < 200; ++f)
        run.frame();
    CHECK(run.lpv.schedule().load.rsmSize == 64);
    CHECK(run.lpv.resolutionDivisor() == 4);
    CHECK(run.renderer.indirectDivisor() == 4);
    const std::string report = engine::profileSummaryMarkdown(run.profiler);
    CHECK(report.find("gi.resolution=quarter (was half): frame ") != std::string::npos);
    CHECK(report.find("with every knob at its floor") != std::string::npos);
}

namespace {

// The frames part's PC settings at console formats, as lpv_bench predicts them (3 cascades of 32^3, 8
// iterations, 2 bounces, occlusion, glossy, RGBA8, RSM 128^2, gi.resolution=half) under adapt in the atrium
// at 1280x720, every pass recorded with its work counts, the bilateral rebuild included (gi.rebuild). The
// consoles' 3 MiB of GI memory do not hold these 5 MiB (gi/presets/console.toml is sized to), so the
// memory budget is lifted: this is about time. Returns the worst predicted GI ms of the last 8 frames (two
// coarse update cycles at the floor) after `frames` frames.
struct PcSettingsOnConsole {
    platforms::PlatformProfile profile;
    AdaptedLpv run;
    double first = 0, lastWorst = 0;

    PcSettingsOnConsole(const char* console, float atriumDetail,
                        const char* rsmLodTexels = "gi.rsm_lod_texels=0.5")
        : profile(liftedMemory(console)),
          run(profile,
              {"gi.enabled=true", "gi.sh_format=rgba8", "gi.rsm_size=128", "gi.vpl_count=1024",
               "gi.cascades=3", "gi.iterations=8", "gi.bounces=2", "gi.occlusion=true", "gi.glossy=true",
               "gi.resolution=half", "gi.cell_size=1.0", "gi.budget_policy=adapt", rsmLodTexels},
              engine::buildAtrium(atriumDetail), 1280, 720) {
        const int frames = 240;
        for (int f = 0; f < frames; ++f) {
            const auto cost = run.frame();
            if (cost && first == 0) first = cost->ms;
            if (cost && f >= frames - 8) lastWorst = std::max(lastWorst, cost->ms);
        }
        const GiLoad& load = run.lpv.schedule().load;
        MESSAGE(std::string(console) << ", atrium of " << run.scene.triangleCount()
                                     << " triangles: predicted GI " << first
                                     << " ms on the first checked frame, at most " << lastWorst
                                     << " ms over the last 8 frames; coarse cascades every "
                                     << load.coarseUpdateInterval << " frames, " << load.iterations
                                     << " iterations, RSM " << load.rsmSize << ", lookup every "
                                     << load.resolutionDivisor << " pixels, " << load.bounces << " bounces");
    }
    static platforms::PlatformProfile liftedMemory(const char* console) {
        platforms::PlatformProfile p = platforms::loadPlatformProfile(console);
        p.giMemoryBudgetBytes = 64ull << 20;
        return p;
    }
};

} // namespace

TEST_CASE("gi budget: adapt brings the PC settings under 3.3 ms on both consoles through the real pipeline") {
    // About 100k triangles (scene detail 0.4), the scene lpv_bench's console figures assume.
    for (const char* console : {"x360", "ps3"}) {
        SUBCASE(console) {
            PcSettingsOnConsole pc(console, 0.4f);
            CHECK(pc.run.scene.triangleCount() < 110000);
            // As configured: about 1.9x over (2.0-2.2x before the RSMs drew levels of detail).
            CHECK(pc.first > 1.8 * pc.profile.giBudgetMs);
            CHECK(pc.lastWorst > 0.0);
            CHECK(pc.lastWorst <= pc.profile.giBudgetMs);
            CHECK(pc.run.lpv.schedule().stepsInEffect > 0);
            CHECK(!pc.run.lpv.schedule().timeOverBudget);
            // At the floor each coarse update runs in halves on frames of their own: over the
            // frames the profiler kept, no frame draws a coarse cascade's RSM and propagates it,
            // the finest cascade runs whole every frame, and every coarse half does run.
            const auto& scopes = pc.run.profiler.scopes();
            uint64_t newest = 0;
            pc.run.profiler.forEachFrame(
                [&](const engine::FrameProfiler::FrameRecord& r) { newest = std::max(newest, r.frame); });
            uint32_t frames = 0, lightHalves = 0, volumeHalves = 0;
            pc.run.profiler.forEachFrame([&](const engine::FrameProfiler::FrameRecord& r) {
                if (r.frame + 16 <= newest) return; // the last 16 frames, at the floor
                ++frames;
                for (uint32_t c = 0; c < 3; ++c) {
                    const std::string cascade = "gi/cascade" + std::to_string(c);
                    bool rsm = false, propagate = false;
                    for (uint32_t k = 0; k < r.sampleCount; ++k) {
                        const std::string& path = scopes[r.samples[k].scope].path;
                        rsm = rsm || path == cascade + "/rsm";
                        propagate = propagate || path == cascade + "/propagate";
                    }
                    if (c == 0) {
                        CHECK(rsm);
                        CHECK(propagate);
                        continue;
                    }
                    CHECK_FALSE((rsm && propagate));
                    lightHalves += rsm ? 1 : 0;
                    volumeHalves += propagate ? 1 : 0;
                }
            });
            // 2 coarse cascades, each with a light half and a volume half every 4 frames.
            CHECK(frames == 16);
            CHECK(lightHalves == frames / 2);
            CHECK(volumeHalves == frames / 2);
        }
    }
}

TEST_CASE("gi budget: in the full atrium the PS3 fits with the RSMs' levels of detail; with full meshes it "
          "stays over with every knob at its floor, and the report says so") {
    // 258k triangles: the RSM of the finest cascade, which sees them all and updates every frame,
    // is bound by the PS3's triangle setup (about 0.9 ms in full). Levels of detail within half a
    // texel of the map (which grows as the scheduler shrinks the map) take most of them away.
    PcSettingsOnConsole lod("ps3", 1.0f);
    CHECK(lod.lastWorst <= lod.profile.giBudgetMs);
    CHECK(!lod.run.lpv.schedule().timeOverBudget);

    PcSettingsOnConsole pc("ps3", 1.0f, "gi.rsm_lod_texels=0");
    CHECK(pc.lastWorst > pc.profile.giBudgetMs);
    const GiLoad& load = pc.run.lpv.schedule().load;
    CHECK(load.coarseUpdateInterval == 4);
    CHECK(load.iterations == 4);
    CHECK(load.rsmSize == 64);
    CHECK(load.resolutionDivisor == 4);
    CHECK(load.bounces == 1);
    CHECK(pc.run.lpv.schedule().timeOverBudget);
    const std::string report = engine::profileSummaryMarkdown(pc.run.profiler);
    CHECK(report.find("with every knob at its floor") != std::string::npos);
}

TEST_CASE("gi: changing gi.cascades while the game runs remakes the cascades (with the game's frame loop)") {
    AdaptedLpv run(platforms::loadPlatformProfile("pc"),
                   {"gi.enabled=true", "gi.cascades=3", "gi.budget_policy=fixed"}, engine::buildCornellBox(),
                   160, 120);
    run.frame();
    CHECK(run.lpv.cascadeCount() == 3);
    for (const uint32_t cascades : {2u, 4u, 1u, 3u}) {
        run.config.applyOverride("gi.cascades=" + std::to_string(cascades), "test");
        run.frame();
        CHECK(run.lpv.cascadeCount() == cascades);
        CHECK(run.lpv.settings().cascades == cascades);
    }
}

TEST_CASE("gi budget: a change of the RSM size or the bounces keeps the cascades' results; a change of "
          "the volumes makes every cascade again") {
    // The first two are adapt's knobs: had they made every cascade again, the frame after each such
    // step would run both coarse cascades instead of the one scheduled (a spike of a whole coarse
    // update, over budget on PS3 after the bounce step: 3.62 ms against 2.97 in the cycles after).
    AdaptedLpv run(platforms::loadPlatformProfile("pc"),
                   {"gi.enabled=true", "gi.cascades=3", "gi.coarse_update_interval=2", "gi.occlusion=true",
                    "gi.bounces=2", "gi.budget_policy=fixed"},
                   engine::buildCornellBox(), 160, 120);
    for (int i = 0; i < 4; ++i)
        run.frame();
    struct Change {
        const char* setting;
        bool makesEveryCascade;
        uint64_t frame = 0;
    };
    std::vector<Change> changes = {{"gi.rsm_size=128", false},
                                   {"gi.bounces=1", false},
                                   {"gi.bounces=2", false},
                                   {"gi.rsm_size=256", false},
                                   {"gi.grid_size=24", true}};
    for (Change& c : changes) {
        run.config.applyOverride(c.setting, "test");
        c.frame = run.device->frameIndex() + 1; // the index the profiler records the frame under
        run.frame();
        run.frame();
    }
    for (int i = 0; i < 4; ++i) // until the profiler has checked the last change's frame
        run.frame();
    CHECK(run.lpv.settings().rsmSize == 256);
    CHECK(run.lpv.settings().bounces == 2);
    const auto& scopes = run.profiler.scopes();
    for (const Change& c : changes) {
        int coarsePropagated = -1;
        run.profiler.forEachFrame([&](const engine::FrameProfiler::FrameRecord& r) {
            if (r.frame != c.frame) return;
            coarsePropagated = 0;
            for (uint32_t k = 0; k < r.sampleCount; ++k) {
                const std::string& path = scopes[r.samples[k].scope].path;
                // A cascade made anew is injected (its propagation may run with the others').
                coarsePropagated += path == "gi/cascade1/inject" || path == "gi/cascade2/inject" ? 1 : 0;
            }
        });
        INFO(c.setting);
        CHECK(coarsePropagated == (c.makesEveryCascade ? 2 : 1));
    }
}

TEST_CASE("gi: a change of gi.rsm_size or gi.vpl_count made while GI is off applies when it comes back on") {
    AdaptedLpv run(platforms::loadPlatformProfile("pc"),
                   {"gi.enabled=true", "gi.rsm_size=256", "gi.vpl_count=4096", "gi.budget_policy=fixed"},
                   engine::buildCornellBox(), 160, 120);
    run.frame();
    // The gather's VPL windows (one buffer per gathered cascade) hold their counts besides lists
    // that shrink with the VPLs.
    const auto windowCounts = [&] {
        const gi::LpvSettings& s = run.lpv.settings();
        return s.gather ? std::min(s.cascades, gi::VplGather::kCascades) * gi::VplWindows::kCountBytes : 0;
    };
    const uint64_t rsmBytes = run.device->allocations().bytesIn("gi.rsm"),
                   vplBytes = run.device->allocations().bytesIn("gi.vpl") - windowCounts();
    for (const char* s : {"gi.enabled=false", "gi.rsm_size=128", "gi.vpl_count=1024"}) {
        run.config.applyOverride(s, "test");
        run.frame();
    }
    run.config.applyOverride("gi.enabled=true", "test");
    run.frame();
    // A quarter of the RSM's texels and of the VPLs: the resources were made again at the new sizes.
    CHECK(run.device->allocations().bytesIn("gi.rsm") * 4 == rsmBytes);
    CHECK((run.device->allocations().bytesIn("gi.vpl") - windowCounts()) * 4 == vplBytes);
}
