// Overlay bars and labels from the profiler's window statistics.
#include "engine/profiler/ProfilerOverlay.h"

#include "EngineShaders.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/OverlayText.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace lpv::engine {
namespace {

constexpr glm::vec4 kTextColor{0.93f, 0.93f, 0.93f, 1.0f};
constexpr glm::vec4 kOverColor{0.9f, 0.15f, 0.1f, 0.9f};

// Appends the scopes under `parent` to `order`, depth first (children in the order they first ran,
// so a pass first run on a later frame, such as a bounce left to the next one, still sits under
// its parent), up to order's size; recursion as deep as the scopes nest.
void depthFirst(const std::vector<ScopeInfo>& scopes, int32_t parent, std::span<uint32_t> order,
                uint32_t& count) {
    for (uint32_t i = 0; i < scopes.size() && count < order.size(); ++i)
        if (scopes[i].parent == parent) {
            order[count++] = i;
            depthFirst(scopes, int32_t(i), order, count);
        }
}

// A pass's median: GPU where timed, else CPU.
double medianMs(const ScopeInfo& s) {
    return s.gpuMs.count() ? s.gpuMs.stats().median : s.cpuMs.stats().median;
}

} // namespace

ProfilerOverlay::ProfilerOverlay(rhi::Device& device) : device_(device), rects_(kMaxRects) {
    rhi::GraphicsPipelineDesc d;
    d.vertex = &shaders::overlay_vert;
    d.fragment = &shaders::overlay_frag;
    d.colorFormats = {rhi::Format::RGBA8Srgb};
    d.blend = {rhi::BlendState::alpha()};
    d.debugName = "profiler overlay";
    pipeline_ = device.createPipeline(d);
    rectsBuffer_ =
        device.createBuffer({sizeof(OverlayRect) * kMaxRects, rhi::kBufferStorage | rhi::kBufferTransfer,
                             rhi::MemoryAccess::GpuOnly, "profiler overlay rects", "profiler.overlay"});
}

ProfilerOverlay::~ProfilerOverlay() {
    device_.waitIdle();
    device_.destroy(pipeline_);
    device_.destroy(rectsBuffer_);
}

uint32_t ProfilerOverlay::layout(const FrameProfiler& profiler, uint32_t width, uint32_t height,
                                 std::span<OverlayRect> out) {
    // Rows of 13 pixels shrink to fit the target's height (a 640x360 window holds the GI's 30-odd
    // passes at 10 pixels a row), down to 3; passes that would still run off the bottom are left out.
    // The rows: the frame's, one a pass, and with labels a last one for the GI total.
    const float x0 = 12.0f, y0 = 12.0f, maxRow = 13.0f, minRow = 3.0f;
    const float available = float(height) - 2.0f * y0;
    std::array<uint32_t, kMaxRows> order;
    uint32_t scopes = 0;
    depthFirst(profiler.scopes(), -1, order, scopes);
    float row = 0.0f;
    uint32_t passes = 0;
    const auto fit = [&](uint32_t otherRows) {
        // Whole pixels a row, so bars keep a gap; the fit is counted in whole rows too (a float
        // quotient of 41.99999 rows left the last pass out).
        row = std::clamp(std::floor(available / float(scopes + otherRows)), minRow, maxRow);
        passes = std::min(scopes,
                          uint32_t(std::max(std::floor(available / row + 1e-3f) - float(otherRows), 0.0f)));
    };
    fit(2);

    // Labels: the names in a column left of the bars (indented by depth), the medians in one
    // right of them, where a row holds a glyph and the bars keep a useful width.
    const float indentStep = 6.0f, labelGap = 6.0f;
    const float valueWidth = overlayTextWidth("0000.00");
    float nameWidth = overlayTextWidth("frame");
    for (uint32_t i = 0; i < passes; ++i) {
        const ScopeInfo& s = profiler.scopes()[order[i]];
        nameWidth = std::max(nameWidth, indentStep * float(s.depth) + overlayTextWidth(s.name));
    }
    const float labelledBudget =
        std::min(400.0f, (float(width) - 2.0f * x0 - nameWidth - valueWidth - 2.0f * labelGap) / 1.5f);
    const bool labelled = row >= kOverlayTextHeight + 1.0f && labelledBudget >= 48.0f;
    if (!labelled) fit(1);
    const uint32_t rows = passes + (labelled ? 2 : 1);
    const float barHeight = std::round(row * 10.0f / 13.0f), gap = row - barHeight;
    // Pixels for the whole frame budget; bars stop at 1.5 budgets.
    const float budgetWidth = labelled ? labelledBudget : std::min(400.0f, float(width) * 0.4f);
    const float barsX = labelled ? x0 + nameWidth + labelGap : x0;
    const float valuesX = barsX + budgetWidth * 1.5f + labelGap;
    const float right = labelled ? valuesX + valueWidth : barsX + budgetWidth * 1.5f;
    const float msToPixels = budgetWidth / float(profiler.profile().frameBudgetMs);
    const FrameBudgetCheck& check = profiler.lastBudgetCheck();
    const bool over = check.frameOverBudget || check.giOverBudget || check.giPredictedOverBudget;

    uint32_t n = 0;
    const auto rect = [&](glm::vec4 r, glm::vec4 c) {
        if (n < out.size()) out[n++] = {r, c};
    };
    const auto text = [&](std::string_view s, float x, float y, glm::vec4 c) {
        n = overlayTextRects(s, x, y, c, out, n);
    };
    const auto rowY = [&](uint32_t r) { return y0 + float(r) * (barHeight + gap); };
    // Text centred on its bar, on whole pixels.
    const auto textY = [&](uint32_t r) {
        return std::floor(rowY(r) + (barHeight - kOverlayTextHeight) * 0.5f);
    };

    rect({x0 - 4, y0 - 4, right - x0 + 8, float(rows) * (barHeight + gap) + 8}, {0, 0, 0, 0.55f});
    // Whole frame, then one bar per pass (unlabelled, children indented by depth).
    const SampleStats frame = profiler.frameGpuMs().count ? profiler.frameGpuMs() : profiler.frameCpuMs();
    rect({barsX, rowY(0), std::min(float(frame.median) * msToPixels, budgetWidth * 1.5f), barHeight},
         over ? kOverColor : glm::vec4(0.85f, 0.85f, 0.85f, 0.9f));
    // Each pass's median once (a window's statistics sort its samples), for its bar and its label.
    std::array<double, kMaxRows> medians;
    for (uint32_t i = 0; i < passes; ++i) {
        const ScopeInfo& s = profiler.scopes()[order[i]];
        medians[i] = medianMs(s);
        const float indent = labelled ? 0.0f : 8.0f * float(s.depth);
        const bool gi = s.path.starts_with("gi");
        rect({barsX + indent, rowY(i + 1), std::min(float(medians[i]) * msToPixels, budgetWidth * 1.5f),
              barHeight},
             gi ? glm::vec4(0.95f, 0.6f, 0.15f, 0.9f) : glm::vec4(0.3f, 0.55f, 0.9f, 0.9f));
    }
    // The frame budget line, before the labels, which are what a full buffer leaves out.
    rect({barsX + budgetWidth, y0 - 4, 2, float(rows) * (barHeight + gap) + 8}, {1, 0.2f, 0.2f, 1});
    if (!labelled) return n;
    char value[32];
    text("frame", x0, textY(0), kTextColor);
    std::snprintf(value, sizeof(value), "%.2f", frame.median);
    text(value, valuesX, textY(0), over ? kOverColor : kTextColor);
    for (uint32_t i = 0; i < passes; ++i) {
        const ScopeInfo& s = profiler.scopes()[order[i]];
        text(s.name, x0 + indentStep * float(s.depth), textY(i + 1), kTextColor);
        // A pass timed inside another's scope (gi.rebuild, in render.lighting) has no time of its
        // own to show.
        if (s.timedIn.empty()) std::snprintf(value, sizeof(value), "%.2f", medians[i]);
        text(s.timedIn.empty() ? value : "-", valuesX, textY(i + 1), kTextColor);
    }
    // The GI total against the GI budget, as the budget check holds it: on a profile whose GI time
    // is predicted (x360, ps3) the console's predicted time, not this device's.
    const platforms::PlatformProfile& profile = profiler.profile();
    char total[112]; // a custom profile's long name is cut short
    if (profile.giTimePredicted)
        std::snprintf(total, sizeof(total), "GI %.2f of %.2f ms predicted on %s (%.2f measured here)",
                      check.giPredictedMs, profile.giBudgetMs, profile.name.c_str(), check.giMs);
    else
        std::snprintf(total, sizeof(total), "GI %.2f of %.2f ms", check.giMs, profile.giBudgetMs);
    // Red when the time it names first is over (the measured one also puts the frame's bar in red).
    const bool giOver = profile.giTimePredicted ? check.giPredictedOverBudget : check.giOverBudget;
    text(total, x0, textY(passes + 1), giOver ? kOverColor : kTextColor);
    return n;
}

void ProfilerOverlay::draw(rhi::CommandList& cmd, const FrameProfiler& profiler, rhi::TextureHandle output) {
    const rhi::TextureDesc& desc = device_.desc(output);
    const uint32_t n = layout(profiler, desc.width, desc.height, rects_);
    // updateBuffer takes up to 64 KiB at a time (vkCmdUpdateBuffer's limit).
    const uint64_t bytes = uint64_t(n) * sizeof(OverlayRect);
    for (uint64_t offset = 0; offset < bytes; offset += 65536)
        cmd.updateBuffer(rectsBuffer_, offset, reinterpret_cast<const char*>(rects_.data()) + offset,
                         uint32_t(std::min<uint64_t>(65536, bytes - offset)));
    const glm::vec4 viewport(float(desc.width), float(desc.height), 0, 0);
    rhi::RenderPassDesc pass;
    pass.colors[0] = {output, 0, 0, rhi::LoadOp::Load};
    pass.colorCount = 1;
    pass.debugName = "profiler overlay";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &viewport, sizeof(viewport));
    cmd.bindStorageBuffer(1, rectsBuffer_);
    cmd.draw(6 * n);
    cmd.endRenderPass();
}

} // namespace lpv::engine
