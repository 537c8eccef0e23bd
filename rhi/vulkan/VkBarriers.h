// The RHI's automatic, conservative barriers (see CommandList.h): every texture mip has a tracked
// layout; moving it waits for all earlier commands and makes all earlier writes visible to all later
// commands. Coarse on purpose: correct for every use the RHI allows, and the validation layer
// (synchronization validation included) has nothing to report.
#pragma once

#include "VkResources.h"

#include <vulkan/vulkan.h>

#include <array>

namespace lpv::rhi::vk {

// Barriers that go into one vkCmdPipelineBarrier2: a driver may drain its pipeline once per call
// (NVIDIA's does), so a render pass's layout moves and its memory barrier are recorded together.
// Fixed storage, no heap. Flushed by flush() or at the end of its scope; recorded outside a dynamic
// rendering instance.
class BarrierBatch {
public:
    explicit BarrierBatch(VkCommandBuffer cmd) : cmd_(cmd) {}
    ~BarrierBatch() { flush(); }
    BarrierBatch(const BarrierBatch&) = delete;
    BarrierBatch& operator=(const BarrierBatch&) = delete;

    // Moves mips [baseMip, baseMip + mipCount) of `texture` to `layout` (nothing for mips already
    // there; the tracked layouts change now, so a later move in the same batch sees them).
    void transition(VulkanTexture& texture, uint32_t baseMip, uint32_t mipCount, VkImageLayout layout);
    // Back to the texture's home layout, all mips.
    void transitionHome(VulkanTexture& texture) {
        transition(texture, 0, texture.desc.mipLevels, texture.home);
    }
    // All earlier writes visible to every later stage and access.
    void memory() { memory_ = true; }
    // All earlier writes made available to the host (for MemoryAccess::HostRead buffers, read after the
    // frame's fence, which covers device access only), in the same call.
    void hostRead() { hostRead_ = true; }
    // Nothing to record yet.
    bool empty() const { return imageCount_ == 0 && !memory_ && !hostRead_; }
    void flush();

private:
    VkCommandBuffer cmd_;
    std::array<VkImageMemoryBarrier2, 32> images_; // the first imageCount_ are set, each when added
    uint32_t imageCount_ = 0;
    bool memory_ = false;
    bool hostRead_ = false;
};

// Every vkCmdPipelineBarrier2 of the backend goes through here, which counts it.
void cmdPipelineBarrier2(VkCommandBuffer cmd, const VkDependencyInfo& dep);
// vkCmdPipelineBarrier2 calls recorded so far on this thread (a device records on one thread):
// a command list counts its frame's by difference.
uint64_t pipelineBarrierCalls();

// A full memory barrier: all earlier writes visible to every later stage and access.
void fullBarrier(VkCommandBuffer cmd);

// One texture's move, as BarrierBatch::transition, recorded at once.
inline void transition(VkCommandBuffer cmd, VulkanTexture& texture, uint32_t baseMip, uint32_t mipCount,
                       VkImageLayout layout) {
    BarrierBatch(cmd).transition(texture, baseMip, mipCount, layout);
}

// Back to the texture's home layout, all mips.
inline void transitionHome(VkCommandBuffer cmd, VulkanTexture& texture) {
    BarrierBatch(cmd).transitionHome(texture);
}

} // namespace lpv::rhi::vk
