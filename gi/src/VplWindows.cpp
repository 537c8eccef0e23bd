// The VPL windows pass: one workgroup per phase and window over a cascade's cluster grid.
#include "gi/VplWindows.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

namespace lpv::gi {
namespace {

// std140 block `Params` of vpl_windows.comp.
struct WindowUniforms {
    glm::vec4 within;
    glm::vec4 beyond;
    glm::ivec4 sizes;
};

glm::vec4 boxOf(const std::optional<VolumeGrid>& g) {
    return g ? glm::vec4(g->origin, g->cellSize) : glm::vec4(0.0f);
}

} // namespace

VplWindows::VplWindows(rhi::Device& device) : device_(device) {
    pipeline_ = device.createPipeline(rhi::ComputePipelineDesc{&shaders::vpl_windows_comp, "vpl windows"});
}

VplWindows::~VplWindows() {
    device_.destroy(pipeline_);
}

void VplWindows::record(rhi::CommandList& cmd, rhi::BufferHandle vpls, uint32_t side,
                        std::optional<VolumeGrid> within, std::optional<VolumeGrid> beyond,
                        rhi::BufferHandle lists) {
    // The shader's boxes share one cell count: every cascade has the finest's (LpvVolumes).
    const uint32_t cells = within ? within->size : beyond ? beyond->size : 1;
    WindowUniforms u;
    u.within = boxOf(within);
    u.beyond = boxOf(beyond);
    u.sizes = glm::ivec4(int(side), int(cells), int(room(side)), 0);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindStorageBuffer(1, vpls);
    cmd.bindStorageBuffer(2, lists);
    cmd.dispatch(kPhases, kWindows, 1);
}

engine::WorkCounts vplWindowsWork(uint32_t side) {
    const uint64_t slots = 2ull * side * side;
    engine::WorkCounts w;
    w.bytesMoved = VplWindows::kWindows * slots * (48 + 4);
    w.aluOps = VplWindows::kWindows * slots * 20;
    return w;
}

} // namespace lpv::gi
