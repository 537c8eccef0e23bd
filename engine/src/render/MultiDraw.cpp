// Indirect multi-draws: the commands' ring and the calls.
#include "engine/render/MultiDraw.h"

#include <algorithm>
#include <stdexcept>

namespace lpv::engine {

void addDrawIndexStream(rhi::GraphicsPipelineDesc& desc) {
    if (desc.vertexBuffers.size() != kDrawIndexSlot)
        throw std::logic_error(desc.debugName + ": the draw index stream goes after the vertex buffer");
    desc.vertexBuffers.push_back({sizeof(uint32_t), true});
    desc.attributes.push_back({kDrawIndexAttribute, rhi::VertexFormat::UInt1, 0, kDrawIndexSlot});
}

MultiDraw::MultiDraw(rhi::Device& device, std::string debugName, std::string memoryCategory)
    : device_(device), debugName_(std::move(debugName)), category_(std::move(memoryCategory)) {}

MultiDraw::~MultiDraw() {
    if (commands_) device_.destroy(commands_);
    for (const Retired& r : retired_)
        device_.destroy(r.buffer);
}

void MultiDraw::reserve(uint32_t draws) {
    if (draws > capacity_) grow(draws);
}

void MultiDraw::grow(uint32_t draws) {
    // This frame's commands may already name the buffer: it goes when no frame can read it.
    rhi::BufferHandle old = commands_;
    const rhi::DrawIndexedIndirectCommand* gathered = old ? region() + used_ : nullptr;
    capacity_ = draws;
    const uint64_t bytes =
        uint64_t(capacity_) * device_.caps().framesInFlight * sizeof(rhi::DrawIndexedIndirectCommand);
    commands_ = device_.createBuffer({bytes, rhi::kBufferIndirect, rhi::MemoryAccess::HostWrite,
                                      debugName_ + " draw commands", category_});
    // What add() gathered and draw() has not drawn yet moves to the start of the new region.
    if (gathered) std::copy_n(gathered, pending_, region());
    used_ = 0;
    if (old) retired_.push_back({old, device_.frameIndex()});
}

rhi::DrawIndexedIndirectCommand* MultiDraw::region() {
    const uint64_t slot = device_.frameIndex() % device_.caps().framesInFlight;
    return static_cast<rhi::DrawIndexedIndirectCommand*>(device_.mapped(commands_)) + slot * capacity_;
}

void MultiDraw::add(const DrawLod& lod, uint32_t drawIndex) {
    if (frame_ != device_.frameIndex()) {
        frame_ = device_.frameIndex();
        used_ = pending_ = 0;
        // A buffer replaced in frame f is read by no frame once f + framesInFlight has begun.
        std::erase_if(retired_, [&](const Retired& r) {
            if (frame_ < r.frame + device_.caps().framesInFlight) return false;
            device_.destroy(r.buffer);
            return true;
        });
    }
    // More draws in a frame than there is room for (an RSM that several cascades share, drawn once
    // for each): a frame's region cannot wrap onto one in flight, so the buffer grows, once.
    if (used_ + pending_ >= capacity_) grow(std::max(2 * capacity_, 64u));
    region()[used_ + pending_] = {lod.indexCount, 1, lod.firstIndex, 0, drawIndex};
    ++pending_;
}

void MultiDraw::draw(rhi::CommandList& cmd) {
    if (pending_ == 0) return;
    if (device_.caps().multiDrawIndirect) {
        const uint64_t slot = device_.frameIndex() % device_.caps().framesInFlight;
        cmd.drawIndexedIndirect(
            commands_, (slot * capacity_ + used_) * sizeof(rhi::DrawIndexedIndirectCommand), pending_);
    } else {
        const rhi::DrawIndexedIndirectCommand* c = region() + used_;
        for (uint32_t k = 0; k < pending_; ++k)
            cmd.drawIndexed(c[k].indexCount, c[k].instanceCount, c[k].firstIndex, c[k].vertexOffset,
                            c[k].firstInstance);
    }
    used_ += pending_;
    pending_ = 0;
}

} // namespace lpv::engine
