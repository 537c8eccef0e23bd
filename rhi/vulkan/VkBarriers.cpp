// Layout transitions and global memory barriers with synchronization2.
#include "VkBarriers.h"

#include <array>

namespace lpv::rhi::vk {
namespace {

constexpr VkPipelineStageFlags2 kAllStages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
constexpr VkAccessFlags2 kAllWrites = VK_ACCESS_2_MEMORY_WRITE_BIT;
constexpr VkAccessFlags2 kAllAccess = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

// Every earlier write, by every stage, made available to and visible at `dstStages`' `dstAccess`.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 dstStages, VkAccessFlags2 dstAccess) {
    VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    barrier.srcStageMask = kAllStages;
    barrier.srcAccessMask = kAllWrites;
    barrier.dstStageMask = dstStages;
    barrier.dstAccessMask = dstAccess;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &barrier;
    vkCmdPipelineBarrier2(cmd, &dep);
}

} // namespace

void fullBarrier(VkCommandBuffer cmd) {
    memoryBarrier(cmd, kAllStages, kAllAccess);
}

void hostReadBarrier(VkCommandBuffer cmd) {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

void transition(VkCommandBuffer cmd, VulkanTexture& texture, uint32_t baseMip, uint32_t mipCount,
                VkImageLayout layout) {
    // Runs of mips with the same old layout become one barrier; a fixed array keeps this free of
    // heap allocation (16 covers every mip chain up to 32k texels).
    std::array<VkImageMemoryBarrier2, 16> barriers{};
    uint32_t count = 0;
    auto flush = [&] {
        if (count == 0) return;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = count;
        dep.pImageMemoryBarriers = barriers.data();
        vkCmdPipelineBarrier2(cmd, &dep);
        count = 0;
    };
    const uint32_t end = baseMip + mipCount;
    for (uint32_t mip = baseMip; mip < end;) {
        const VkImageLayout old = texture.layouts[mip];
        uint32_t runEnd = mip + 1;
        while (runEnd < end && texture.layouts[runEnd] == old)
            ++runEnd;
        if (old != layout) {
            if (count == barriers.size()) flush();
            VkImageMemoryBarrier2& b = barriers[count++];
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
    flush();
}

} // namespace lpv::rhi::vk
