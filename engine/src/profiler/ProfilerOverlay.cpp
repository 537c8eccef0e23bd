// Overlay bars from the profiler's window statistics.
#include "engine/profiler/ProfilerOverlay.h"

#include "EngineShaders.h"
#include "engine/profiler/FrameProfiler.h"

#include <algorithm>
#include <cmath>

namespace lpv::engine {

ProfilerOverlay::ProfilerOverlay(rhi::Device& device) : device_(device) {
    rhi::GraphicsPipelineDesc d;
    d.vertex = &shaders::overlay_vert;
    d.fragment = &shaders::overlay_frag;
    d.colorFormats = {rhi::Format::RGBA8Srgb};
    d.blend = {rhi::BlendState::alpha()};
    d.debugName = "profiler overlay";
    pipeline_ = device.createPipeline(d);
}

ProfilerOverlay::~ProfilerOverlay() {
    device_.destroy(pipeline_);
}

void ProfilerOverlay::draw(rhi::CommandList& cmd, const FrameProfiler& profiler, rhi::TextureHandle output) {
    const rhi::TextureDesc& desc = device_.desc(output);
    uniforms_.viewport = glm::vec4(float(desc.width), float(desc.height), 0, 0);
    // Rows of 13 pixels shrink to fit the target's height (a 640x360 window holds the GI's 30-odd
    // passes at 10 pixels a row), down to 3; passes that would still run off the bottom are left out.
    const float x0 = 12.0f, y0 = 12.0f, maxRow = 13.0f, minRow = 3.0f;
    const float available = float(desc.height) - 2.0f * y0;
    uint32_t passes = uint32_t(std::min<size_t>(profiler.scopes().size(), kMaxRects - 3));
    // Whole pixels a row, so bars keep a gap; the fit is counted in whole rows too (a float
    // quotient of 41.99999 rows left the last pass out).
    const float row = std::clamp(std::floor(available / float(passes + 1)), minRow, maxRow);
    passes = std::min(passes, uint32_t(std::max(std::floor(available / row + 1e-3f) - 1.0f, 0.0f)));
    const float barHeight = std::round(row * 10.0f / 13.0f), gap = row - barHeight;
    const float budgetWidth = std::min(400.0f, float(desc.width) * 0.4f); // pixels for the whole frame budget
    const float msToPixels = budgetWidth / float(profiler.profile().frameBudgetMs);
    const FrameBudgetCheck& check = profiler.lastBudgetCheck();
    const bool over = check.frameOverBudget || check.giOverBudget || check.giPredictedOverBudget;
    uint32_t n = 0;
    const auto rect = [&](glm::vec4 r, glm::vec4 c) {
        if (n < kMaxRects) {
            uniforms_.rects[n] = r;
            uniforms_.colors[n] = c;
            ++n;
        }
    };
    rect({x0 - 4, y0 - 4, budgetWidth * 1.5f + 8, float(passes + 1) * (barHeight + gap) + 8},
         {0, 0, 0, 0.55f});
    // Whole frame, then one bar per pass (children indented by depth).
    const SampleStats frame = profiler.frameGpuMs().count ? profiler.frameGpuMs() : profiler.frameCpuMs();
    rect({x0, y0, std::min(float(frame.median) * msToPixels, budgetWidth * 1.5f), barHeight},
         over ? glm::vec4(0.9f, 0.15f, 0.1f, 0.9f) : glm::vec4(0.85f, 0.85f, 0.85f, 0.9f));
    for (uint32_t i = 0; i < passes; ++i) {
        const ScopeInfo& s = profiler.scopes()[i];
        const SampleStats st = s.gpuMs.count() ? s.gpuMs.stats() : s.cpuMs.stats();
        const float indent = 8.0f * float(s.depth);
        const bool gi = s.path.starts_with("gi");
        rect({x0 + indent, y0 + float(i + 1) * (barHeight + gap),
              std::min(float(st.median) * msToPixels, budgetWidth * 1.5f), barHeight},
             gi ? glm::vec4(0.95f, 0.6f, 0.15f, 0.9f) : glm::vec4(0.3f, 0.55f, 0.9f, 0.9f));
    }
    // The frame budget line.
    rect({x0 + budgetWidth, y0 - 4, 2, float(passes + 1) * (barHeight + gap) + 8}, {1, 0.2f, 0.2f, 1});
    rhi::RenderPassDesc pass;
    pass.colors[0] = {output, 0, 0, rhi::LoadOp::Load};
    pass.colorCount = 1;
    pass.debugName = "profiler overlay";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &uniforms_, sizeof(uniforms_));
    cmd.draw(6 * n);
    cmd.endRenderPass();
}

} // namespace lpv::engine
