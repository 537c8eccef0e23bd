// The in-window profiler overlay: one bar per pass (GPU median where timed, else CPU), scaled so
// the frame budget spans a fixed width and drawn with the budget line; a bar turns red when the
// frame is over budget. Drawn over the tone-mapped output with alpha blending; no text. Rows
// shrink to fit the output's height, and passes that still would not fit are left out.
#pragma once

#include "rhi/Device.h"

#include <glm/vec4.hpp>

namespace lpv::engine {

class FrameProfiler;

class ProfilerOverlay {
public:
    explicit ProfilerOverlay(rhi::Device& device);
    ~ProfilerOverlay();
    ProfilerOverlay(const ProfilerOverlay&) = delete;
    ProfilerOverlay& operator=(const ProfilerOverlay&) = delete;

    void draw(rhi::CommandList& cmd, const FrameProfiler& profiler, rhi::TextureHandle output);

    static constexpr uint32_t kMaxRects = 64;
    struct Uniforms {
        glm::vec4 viewport;
        glm::vec4 rects[kMaxRects];
        glm::vec4 colors[kMaxRects];
    };

private:
    rhi::Device& device_;
    rhi::GraphicsPipelineHandle pipeline_;
    Uniforms uniforms_{};
};

} // namespace lpv::engine
