// The in-window profiler overlay: one bar per pass (GPU median where timed, else CPU), scaled so
// the frame budget spans a fixed width and drawn with the budget line; the frame's bar turns red
// when the frame is over budget. Rows go depth first, as in the printed report. Where the rows are
// tall enough for text and the output wide enough, each is labelled with its pass (indented by
// depth) and its median ms ("-" for a pass timed inside another's scope), and a last row gives the
// GI total against the GI budget as the budget check holds it (on x360 and ps3 the console's
// predicted time, with this device's measured one beside it). Drawn over the tone-mapped output
// with alpha blending. Rows shrink to fit the output's height, and passes that still would not fit
// are left out.
#pragma once

#include "engine/profiler/OverlayText.h"
#include "rhi/Device.h"

#include <span>
#include <vector>

namespace lpv::engine {

class FrameProfiler;

class ProfilerOverlay {
public:
    explicit ProfilerOverlay(rhi::Device& device);
    ~ProfilerOverlay();
    ProfilerOverlay(const ProfilerOverlay&) = delete;
    ProfilerOverlay& operator=(const ProfilerOverlay&) = delete;

    void draw(rhi::CommandList& cmd, const FrameProfiler& profiler, rhi::TextureHandle output);

    // The rectangles draw() draws on an output of width x height, in drawing order (backdrop,
    // bars, budget line, labels), into `out` as far as it holds; returns how many.
    static uint32_t layout(const FrameProfiler& profiler, uint32_t width, uint32_t height,
                           std::span<OverlayRect> out);

    // The most rectangles a frame draws (bars and the labels' glyphs, about 6 a character: a GI
    // frame's 40 rows take about 4,000); labels past it are left out.
    static constexpr uint32_t kMaxRects = 8192;
    // The most passes given a row.
    static constexpr uint32_t kMaxRows = 96;

private:
    rhi::Device& device_;
    rhi::GraphicsPipelineHandle pipeline_;
    rhi::BufferHandle rectsBuffer_;
    std::vector<OverlayRect> rects_; // kMaxRects, made once: a frame allocates nothing
};

} // namespace lpv::engine
