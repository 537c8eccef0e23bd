// The debug views' pipelines and draws.
#include "gi/GiDebugViews.h"

#include "EngineShaders.h"
#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace lpv::gi {
namespace {

// std140 block `Slice` of lpv_slice.frag.
struct SliceUniforms {
    glm::vec4 params;
    glm::ivec4 flags;
};

} // namespace

GiDebugViews::GiDebugViews(rhi::Device& device) : device_(device) {
    using namespace rhi;
    GraphicsPipelineDesc slice;
    slice.vertex = &engine::shaders::fullscreen_vert;
    slice.fragment = &shaders::lpv_slice_frag;
    slice.colorFormats = {Format::RGBA8Srgb};
    slice.debugName = "lpv slice view";
    slicePipeline_ = device.createPipeline(slice);
    GraphicsPipelineDesc points;
    points.vertex = &shaders::vpl_points_vert;
    points.fragment = &shaders::vpl_points_frag;
    points.topology = PrimitiveTopology::PointList;
    points.colorFormats = {Format::RGBA8Srgb};
    points.debugName = "vpl view";
    pointsPipeline_ = device.createPipeline(points);
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

GiDebugViews::~GiDebugViews() {
    device_.destroy(slicePipeline_);
    device_.destroy(pointsPipeline_);
    device_.destroy(pointSampler_);
}

void GiDebugViews::record(rhi::CommandList& cmd, GiDebugView view, const engine::CameraMatrices& camera,
                          rhi::TextureHandle output, const LpvVolumes& volumes, const VolumeGrid& grid,
                          uint32_t slice, std::span<const VplSource> vpls) {
    using namespace rhi;
    if (view == GiDebugView::None || view == GiDebugView::Indirect) return;
    const TextureDesc& d = device_.desc(output);
    RenderPassDesc pass;
    pass.colors[0] = {output, 0, 0, LoadOp::Load};
    pass.colorCount = 1;
    pass.debugName = "gi debug view";
    cmd.beginRenderPass(pass);
    if (view == GiDebugView::VolumeSlice) {
        // The slice in the top-left corner, one square of half the frame height.
        const float side = float(d.height) * 0.5f;
        cmd.setViewport({0, 0, side, side, 0, 1});
        SliceUniforms u;
        const uint32_t z = std::min(slice, grid.size - 1);
        u.params = glm::vec4((float(z) + 0.5f) / float(grid.size), 1.0f / (grid.cellSize * grid.cellSize),
                             volumes.encodeRange(grid), 0);
        u.flags = glm::ivec4(volumes.encoded() ? 1 : 0, 0, 0, 0);
        cmd.bindPipeline(slicePipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        for (uint32_t c = 0; c < 3; ++c)
            cmd.bindTexture(1 + c, volumes.accumulated()[c], pointSampler_);
        cmd.draw(3);
    } else {
        cmd.bindPipeline(pointsPipeline_);
        cmd.pushUniforms(0, &camera.viewProjection, sizeof(camera.viewProjection));
        for (const VplSource& source : vpls) {
            cmd.bindStorageBuffer(1, source.vpls);
            cmd.draw(source.count);
        }
    }
    cmd.endRenderPass();
}

} // namespace lpv::gi
