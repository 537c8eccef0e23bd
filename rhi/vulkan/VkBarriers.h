// The RHI's automatic, conservative barriers (see CommandList.h): every texture mip has a tracked
// layout; moving it waits for all earlier commands and makes all earlier writes visible to all later
// commands. Coarse on purpose: correct for every use the RHI allows, and the validation layer
// (synchronization validation included) has nothing to report.
#pragma once

#include "VkResources.h"

#include <vulkan/vulkan.h>

namespace lpv::rhi::vk {

// A full memory barrier: all earlier writes visible to every later stage and access.
void fullBarrier(VkCommandBuffer cmd);

// Every earlier write made available to the host, for the frame's fence wait to make visible
// (a fence alone covers device access only): MemoryAccess::HostRead buffers.
void hostReadBarrier(VkCommandBuffer cmd);

// Moves mips [baseMip, baseMip + mipCount) of `texture` to `layout` (no-op for mips already
// there). Must be recorded outside a dynamic rendering instance.
void transition(VkCommandBuffer cmd, VulkanTexture& texture, uint32_t baseMip, uint32_t mipCount,
                VkImageLayout layout);

// Back to the texture's home layout, all mips.
inline void transitionHome(VkCommandBuffer cmd, VulkanTexture& texture) {
    transition(cmd, texture, 0, texture.desc.mipLevels, texture.home);
}

} // namespace lpv::rhi::vk
