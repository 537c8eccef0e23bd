// Layout transitions and global memory barriers with synchronization2.
#include "VkBarriers.h"

namespace lpv::rhi::vk {
namespace {

thread_local uint64_t barrierCalls = 0;

constexpr VkPipelineStageFlags2 kAllStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
constexpr VkAccessFlags2 kAllWrites = VK_ACCESS_2_MEMORY_WRITE_BIT;
constexpr VkAccessFlags2 kAllAccess = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

// Every earlier write, by every stage, made available to and visible at `dstStages`' `dstAccess`.
VkMemoryBarrier2 allWritesVisibleAt(VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = kAllStages;
    barrier.srcAccessMask = kAllWrites;
    barrier.dstStageMask = dstStages;
    barrier.dstAccessMask = dstAccess;
    return barrier;
}

} // namespace

void cmdPipelineBarrier2(VkCommandBuffer cmd, const VkDependencyInfo& dep) {
    vkCmdPipelineBarrier2(cmd, &dep);
    ++barrierCalls;
}

uint64_t pipelineBarrierCalls() {
    return barrierCalls;
}

void fullBarrier(VkCommandBuffer cmd) {
    BarrierBatch(cmd).memory();
}

void BarrierBatch::transition(VulkanTexture& texture, uint32_t baseMip, uint32_t mipCount,
                              VkImageLayout layout) {
    // Runs of mips with the same old layout become one barrier.
    const uint32_t end = baseMip + mipCount;
    for (uint32_t mip = baseMip; mip < end;) {
        const VkImageLayout old = texture.layouts[mip];
        uint32_t runEnd = mip + 1;
        while (runEnd < end && texture.layouts[runEnd] == old)
            ++runEnd;
        if (old != layout) {
            if (imageCount_ == images_.size()) flush();
            VkImageMemoryBarrier2& b = images_[imageCount_++];
            b = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            b.srcStageMask = kAllStages;
            b.srcAccessMask = kAllWrites;
            b.dstStageMask = kAllStages;
            b.dstAccessMask = kAllAccess;
            b.oldLayout = old;
            b.newLayout = layout;
            b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            b.image = texture.image;
            b.subresourceRange = {texture.aspect, mip, runEnd - mip, 0, texture.arrayLayers()};
            for (uint32_t m = mip; m < runEnd; ++m)
                texture.layouts[m] = layout;
        }
        mip = runEnd;
    }
}

void BarrierBatch::flush() {
    if (empty()) return;
    std::array<VkMemoryBarrier2, 2> barriers{};
    uint32_t count = 0;
    if (memory_) barriers[count++] = allWritesVisibleAt(kAllStages, kAllAccess);
    if (hostRead_)
        barriers[count++] = allWritesVisibleAt(VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = count;
    dep.pMemoryBarriers = barriers.data();
    dep.imageMemoryBarrierCount = imageCount_;
    dep.pImageMemoryBarriers = images_.data();
    cmdPipelineBarrier2(cmd_, dep);
    imageCount_ = 0;
    memory_ = false;
    hostRead_ = false;
}

} // namespace lpv::rhi::vk
