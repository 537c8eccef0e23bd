// RGBA8 volumes (gi.sh_format=rgba8, the consoles' format) against RGBA16F at the default
// gi.rgba8_range, in scenes of different cell sizes and light: the indirect light alone, as the
// game's gi.debug_view=indirect shows it.
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/profiler/FrameProfiler.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/LightPropagationVolume.h"
#include "gi/Rgba8Clipping.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace lpv;
using namespace lpv::test;

namespace {

// Frames of `scene` from its camera with a profiler, as the game runs them: what the clipping
// check found (its peaks, after the frames in flight came back) and said (the profiler's notes).
struct ClippingRun {
    Image hdr;
    std::array<float, gi::Rgba8Clipping::kCascades> peaks{};
    std::vector<std::string> notes;
};

ClippingRun runClippingCheck(rhi::Device& device, const engine::Scene& scene,
                             const std::vector<std::string>& settings, uint32_t width = 160,
                             uint32_t height = 120) {
    engine::Config config;
    for (const std::string& s : settings)
        config.applyOverride(s, "test");
    ClippingRun run;
    engine::Renderer renderer(device, width, height);
    renderer.setScene(scene);
    const platforms::PlatformProfile pc = platforms::loadPlatformProfile("pc");
    engine::FrameProfiler profiler(device, pc);
    gi::LightPropagationVolume lpv(device, pc);
    const engine::CameraMatrices camera = engine::cameraMatrices(*scene.camera, float(width) / float(height));
    // The first frame's records come back framesInFlight frames later.
    for (uint32_t f = 0; f < device.caps().framesInFlight + 2; ++f) {
        REQUIRE(gi::updateFromConfig(lpv, config, renderer, camera, &profiler).accepted);
        rhi::CommandList& cmd = device.beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, camera, config, &profiler, &lpv);
        profiler.endFrame(cmd);
        device.endFrame();
    }
    device.waitIdle();
    run.hdr = readImage(device, renderer.hdr());
    REQUIRE(lpv.volumes() != nullptr);
    // Only rgba8 volumes clip (the float formats have no check).
    const gi::Rgba8Clipping* clipping = lpv.volumes()->clipping();
    REQUIRE((clipping != nullptr) == lpv.volumes()->encoded());
    if (clipping) {
        CHECK(clipping->peakFrames()[0] >= 1); // the finest cascade is encoded every frame
        run.peaks = clipping->peaks();
    }
    profiler.forEachNote([&](const engine::FrameProfiler::Note& n) {
        if (n.topic() == gi::kRgba8ClippingNoteTopic) run.notes.emplace_back(n.text());
    });
    return run;
}

std::string rangeText(float range) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", double(range));
    return text;
}

} // namespace

TEST_CASE("gi: rgba8 volumes at the default range light the Cornell box and the atrium as rgba16f does") {
    const engine::Scene atrium = engine::buildAtrium(0.25f);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // The Cornell box's 0.2 m cells and its sun through the roof; 3 cascades (0.2, 0.4 and
            // 0.8 m cells) and 2 bounces, as lpv_bench's frames.
            const std::vector<std::string> cornell = {"gi.enabled=true", "render.debug_view=indirect",
                                                      "render.ssao=false", "gi.cell_size=0.2",
                                                      "gi.bounces=2"};
            std::vector<std::string> cornell8 = cornell;
            cornell8.push_back("gi.sh_format=rgba8");
            const LuminanceChange box =
                luminanceChange(renderSceneFrame(*device, engine::buildCornellBox(), cornell).hdr,
                                renderSceneFrame(*device, engine::buildCornellBox(), cornell8).hdr);
            // The atrium's 1 m cells and a brighter sun.
            const LuminanceChange court =
                luminanceChange(renderAtriumIndirect(*device, atrium, "gi.sh_format=rgba16f").hdr,
                                renderAtriumIndirect(*device, atrium, "gi.sh_format=rgba8").hdr);
            MESSAGE(backend.name << ": rgba8 against rgba16f, mean indirect light " << 100.0 * box.meanShift
                                 << "% (Cornell box), " << 100.0 * court.meanShift
                                 << "% (atrium); mean difference per pixel " << 100.0 * box.meanDifference
                                 << "% and " << 100.0 * court.meanDifference << "% of the mean");
            // Measured here (320x240, every backend alike): -0.8% and 5.3% (Cornell box), -1.0% and
            // 8.2% (atrium). With zero between two codes, as before, +12.7% and 18.7%, +14.7% and
            // 20.2%; with that and one range for every cascade, at the old default (2), the Cornell
            // box was 31% too bright and the atrium 33% too dark (640x360).
            CHECK(std::fabs(box.meanShift) < 0.03);
            CHECK(std::fabs(court.meanShift) < 0.03);
            CHECK(box.meanDifference < 0.12);
            CHECK(court.meanDifference < 0.12);
            // And rgba8 did run: 8-bit steps show in every frame.
            CHECK(box.meanDifference > 0.01);
            CHECK(court.meanDifference > 0.01);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: rgba8 volumes that clip say so, and the range they name gets the light back") {
    const engine::Scene box = engine::buildCornellBox();
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const std::vector<std::string> base = {"gi.enabled=true", "render.debug_view=indirect",
                                                   "render.ssao=false", "gi.cell_size=0.2", "gi.bounces=2"};
            std::vector<std::string> half = base;
            half.push_back("gi.sh_format=rgba16f");
            const Image reference = runClippingCheck(*device, box, half).hdr;
            // At the default range the Cornell box's brightest cells clip a little (1.33x measured),
            // under what is reported: nothing is said.
            std::vector<std::string> fits = base;
            fits.push_back("gi.sh_format=rgba8");
            const ClippingRun quiet = runClippingCheck(*device, box, fits);
            const float quietPeak = *std::max_element(quiet.peaks.begin(), quiet.peaks.end());
            MESSAGE(backend.name << ": at the default range the peak read " << quietPeak << "x");
            CHECK(quiet.notes.empty());
            CHECK(quietPeak > 1.0f); // read back, not left at zero
            CHECK(quietPeak < gi::kReportedClipping);
            // A range a third of the default: the indirect light is far too dark (clipped light
            // no longer propagates), and the report names a larger range. Following it, at most
            // twice, ends where what clips is under the report's threshold, and the light is
            // rgba16f's again.
            float range = 4.0f;
            double firstShift = 0.0;
            int rounds = 0;
            for (; rounds < 4; ++rounds) {
                std::vector<std::string> settings = fits;
                settings.push_back("gi.rgba8_range=" + rangeText(range));
                const ClippingRun run = runClippingCheck(*device, box, settings);
                const LuminanceChange change = luminanceChange(reference, run.hdr);
                const float worst = *std::max_element(run.peaks.begin(), run.peaks.end());
                MESSAGE(backend.name << ": gi.rgba8_range " << range << ": peak " << worst << "x, mean "
                                     << 100.0 * change.meanShift << "% of rgba16f's"
                                     << (run.notes.empty() ? std::string() : ": " + run.notes.front()));
                if (rounds == 0) firstShift = change.meanShift;
                if (worst < gi::kReportedClipping) {
                    CHECK(run.notes.empty());
                    CHECK(std::fabs(change.meanShift) < 0.03);
                    break;
                }
                // One note for the run (the clipping does not grow), naming the range and a larger one.
                REQUIRE(run.notes.size() == 1);
                CHECK(run.notes.front().find("gi.rgba8_range (" + rangeText(range) + ")") !=
                      std::string::npos);
                const float next = gi::rangeToHold(range, worst);
                CHECK(next > range * worst);
                CHECK(run.notes.front().find("set gi.rgba8_range to " + rangeText(next) + " or more") !=
                      std::string::npos);
                range = next;
            }
            CHECK(rounds >= 1);
            CHECK(rounds <= 2);
            // Measured (every backend alike): at range 4 the peak read 2.36x with the light 55% too
            // dark; the suggestion (12) read 1.33x, within 1% of rgba16f.
            CHECK(firstShift < -0.2);
            device.expectSilent();
        }
    }
}
