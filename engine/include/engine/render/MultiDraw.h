// A pass's draws of a scene as indirect multi-draws: the pass adds the draws of one batch
// (GpuScene::batches(): they bind the same textures), then draws them in one call. Where the device
// has no multi-draw (Caps::multiDrawIndirect) each goes out as its own drawIndexed.
//
// The commands go to a buffer the CPU writes and the GPU reads (MemoryAccess::HostWrite), one
// region per frame in flight: a frame writes its region after beginFrame() has waited for the frame
// that used it last, so the GPU never reads what the CPU is writing, and no barrier is needed. Its
// memory category is "render.draw_commands" whatever pass draws: command memory, sized by the
// scene's draws and not by the GI's settings, so in no GI budget.
#pragma once

#include "engine/render/GpuScene.h"
#include "rhi/CommandList.h"
#include "rhi/Device.h"
#include "rhi/Pipeline.h"

#include <string>
#include <vector>

namespace lpv::engine {

// Adds to a pipeline the per-instance stream of draw indices (GpuScene::drawIndices() at vertex
// buffer slot kDrawIndexSlot) that a multi-drawn vertex shader reads at DRAW_INDEX_ATTRIBUTE.
void addDrawIndexStream(rhi::GraphicsPipelineDesc& desc);

class MultiDraw {
public:
    MultiDraw(rhi::Device& device, std::string debugName, std::string memoryCategory);
    ~MultiDraw();
    MultiDraw(const MultiDraw&) = delete;
    MultiDraw& operator=(const MultiDraw&) = delete;

    // Room for `draws` commands a frame: makes the buffer when it has less (a new scene), else
    // nothing. A frame that adds more grows it to twice its room (a new buffer: once per doubling,
    // in the frames that first need it, not in every frame).
    void reserve(uint32_t draws);
    // Draw `drawIndex` (GpuDraw::index: its first instance) at level of detail `lod`.
    void add(const DrawLod& lod, uint32_t drawIndex);
    // Draws what add() gathered since the last draw().
    void draw(rhi::CommandList& cmd);

private:
    struct Retired {
        rhi::BufferHandle buffer;
        uint64_t frame; // replaced in
    };
    void grow(uint32_t draws);
    rhi::DrawIndexedIndirectCommand* region();

    rhi::Device& device_;
    std::string debugName_, category_;
    rhi::BufferHandle commands_;
    uint32_t capacity_ = 0;  // commands a frame
    uint64_t frame_ = ~0ull; // the frame whose region `used_` counts in
    uint32_t used_ = 0, pending_ = 0;
    std::vector<Retired> retired_;
};

} // namespace lpv::engine
