// The in-window profiler overlay's layout, without a GPU: each row's label is its pass and its
// median, in the profiler's order, and text is left out where it would not be readable.
#include "../support/TestDevice.h"

#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfilerOverlay.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <glm/vec2.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::engine;

namespace {

// A frame on the null device, whose simulated GPU clock charges 1 us a command: `render` and the
// three GI passes get 1.5, 2.25, 0.75 and 0 ms of dispatches, the same on every run.
void frame(rhi::Device& device, FrameProfiler& profiler) {
    rhi::CommandList& cmd = device.beginFrame();
    profiler.beginFrame(cmd);
    const auto work = [&](int dispatches) {
        for (int i = 0; i < dispatches; ++i)
            cmd.dispatch(1);
    };
    {
        auto render = profiler.scope("render", &cmd);
        work(1500);
        // A pass first run on the third frame (as a bounce left to the next frame): its row
        // still goes under its parent's.
        if (profiler.scopes().size() > 2) auto late = profiler.scope("late", &cmd);
    }
    {
        auto gi = profiler.scope("gi", &cmd);
        {
            auto propagate = profiler.scope("propagate", &cmd);
            work(2250);
        }
        {
            auto lookup = profiler.scope("lookup", &cmd);
            work(750);
        }
    }
    {
        // Timed inside another scope, as gi.rebuild is in render.lighting.
        auto rebuild = profiler.scope("rebuild");
        profiler.setTimedIn("render");
    }
    profiler.endFrame(cmd);
    device.endFrame();
}

// Where `text` is drawn in `rects` at x, y (any where omitted): the offset of its glyphs from the
// text laid out at (0, 0), all in one colour; nothing when it is not there.
std::optional<glm::vec2> find(std::span<const OverlayRect> rects, const std::string& text,
                              std::optional<float> x = {}, std::optional<float> y = {}) {
    std::vector<OverlayRect> glyphs(text.size() * 16);
    glyphs.resize(overlayTextRects(text, 0, 0, glm::vec4(1), glyphs, 0));
    REQUIRE(!glyphs.empty());
    for (size_t j = 0; j + glyphs.size() <= rects.size(); ++j) {
        const glm::vec2 d = glm::vec2(rects[j].rect) - glm::vec2(glyphs[0].rect);
        if ((x && d.x != *x) || (y && d.y != *y)) continue;
        bool same = true;
        for (size_t m = 0; m < glyphs.size() && same; ++m)
            same = rects[j + m].rect == glyphs[m].rect + glm::vec4(d, 0, 0) &&
                   rects[j + m].color == rects[j].color;
        if (same) return d;
    }
    return std::nullopt;
}

// Four such frames, their GPU times collected.
void profile(rhi::Device& device, FrameProfiler& profiler) {
    for (int f = 0; f < 4; ++f)
        frame(device, profiler);
    profiler.collectPending();
}

std::string ms(double v) {
    char s[32];
    std::snprintf(s, sizeof(s), "%.2f", v);
    return s;
}

} // namespace

TEST_CASE("profiler overlay: each row is labelled with its pass, indented by depth, and its median") {
    auto device = test::nullDevice();
    FrameProfiler profiler(*device, platforms::loadPlatformProfile("pc"));
    profile(*device, profiler);
    REQUIRE(profiler.scopes().size() == 6);
    REQUIRE(profiler.scopes()[5].name == "late");
    // What the labels must say: the simulated medians (the timestamps' own commands add under 0.01 ms).
    const auto median = [&](size_t i) { return profiler.scopes()[i].gpuMs.stats().median; };
    CHECK(median(0) == doctest::Approx(1.5).epsilon(0.005));
    CHECK(median(2) == doctest::Approx(2.25).epsilon(0.005));
    CHECK(median(3) == doctest::Approx(0.75).epsilon(0.005));

    std::vector<OverlayRect> rects(ProfilerOverlay::kMaxRects);
    rects.resize(ProfilerOverlay::layout(profiler, 640, 360, rects));
    // The names in the profiler's order, top to bottom, indented 6 pixels a level.
    struct Row {
        std::string name;
        float x;
        std::string value;
    };
    const double frameMs =
        profiler.frameGpuMs().count ? profiler.frameGpuMs().median : profiler.frameCpuMs().median;
    const std::vector<Row> rows = {{"frame", 12, ms(frameMs)},
                                   {"render", 12, ms(median(0))},
                                   {"late", 18, ms(profiler.scopes()[5].gpuMs.stats().median)},
                                   {"gi", 12, ms(median(1))},
                                   {"propagate", 18, ms(median(2))},
                                   {"lookup", 18, ms(median(3))},
                                   {"rebuild", 12, "-"}};
    float lastY = -1;
    std::optional<float> valuesX;
    for (const Row& row : rows) {
        CAPTURE(row.name);
        const auto name = find(rects, row.name, row.x);
        REQUIRE(name);
        CHECK(name->y > lastY);
        lastY = name->y;
        // Its median on the same row, in one column right of the bars (the first row's places it).
        const auto value = find(rects, row.value, valuesX, name->y);
        REQUIRE(value);
        if (!valuesX) valuesX = value->x;
        CHECK(value->x > row.x + overlayTextWidth(row.name) + 48);
    }
    // Last, the GI total against the budget, as the budget check holds it ("gi" alone here: the
    // top-level GI scopes), over the pc profile's 1.67 ms.
    const engine::FrameBudgetCheck& check = profiler.lastBudgetCheck();
    CHECK(check.giBudgetedMs == doctest::Approx(median(1)));
    const auto total = find(rects, "GI " + ms(check.giBudgetedMs) + " of 1.67 ms", 12.0f);
    REQUIRE(total);
    CHECK(total->y > lastY);
    MESSAGE("640x360, 6 passes: " << rects.size() << " rectangles");
}

TEST_CASE("profiler overlay: rows too short for text, or an output too narrow, get bars only") {
    auto device = test::nullDevice();
    FrameProfiler profiler(*device, platforms::loadPlatformProfile("pc"));
    profile(*device, profiler);
    std::vector<OverlayRect> rects(ProfilerOverlay::kMaxRects);
    // The backdrop, the frame's bar, a bar per pass and the budget line.
    const uint32_t bars = uint32_t(profiler.scopes().size()) + 3;
    CHECK(ProfilerOverlay::layout(profiler, 640, 360, rects) > bars);
    CHECK(ProfilerOverlay::layout(profiler, 640, 60, rects) == bars);  // 6 rows in 36 pixels: 6 a row
    CHECK(ProfilerOverlay::layout(profiler, 120, 360, rects) == bars); // no room for a name column
    // A full buffer keeps the bars and the budget line and leaves labels out.
    std::vector<OverlayRect> few(bars + 5);
    CHECK(ProfilerOverlay::layout(profiler, 640, 360, few) == few.size());
    CHECK(few[bars - 1].rect.z == 2.0f); // the budget line, 2 pixels wide
}

// On a console profile the GI row gives the console's predicted time, which the budget holds, and
// this device's measured one beside it.
TEST_CASE(
    "profiler overlay: on a console profile the GI total is the predicted time, the measured one beside it") {
    auto device = test::nullDevice();
    FrameProfiler profiler(*device, platforms::loadPlatformProfile("x360"));
    profile(*device, profiler);
    const engine::FrameBudgetCheck& check = profiler.lastBudgetCheck();
    std::vector<OverlayRect> rects(ProfilerOverlay::kMaxRects);
    rects.resize(ProfilerOverlay::layout(profiler, 640, 360, rects));
    char expected[128];
    std::snprintf(expected, sizeof(expected), "GI %.2f of 3.30 ms predicted on x360 (%.2f measured here)",
                  check.giPredictedMs, check.giMs);
    CAPTURE(expected);
    CHECK(find(rects, expected, 12.0f));
}
