// Translation of the RHI's API-neutral enums (formats, usages, pipeline state) to Vulkan's.
#pragma once

#include "rhi/CommandList.h"
#include "rhi/Format.h"
#include "rhi/Pipeline.h"
#include "rhi/Resources.h"

#include <vulkan/vulkan.h>

namespace lpv::rhi::vk {

VkFormat toVkFormat(Format f);
VkFormat toVkFormat(VertexFormat f);
VkImageAspectFlags aspectOf(Format f);
VkImageUsageFlags toVkImageUsage(uint32_t usage, Format f);
VkBufferUsageFlags toVkBufferUsage(uint32_t usage);
// The layout a texture rests in between passes and transfers, derived from its usage.
VkImageLayout homeLayout(uint32_t usage, Format f);
VkCompareOp toVkCompare(CompareOp op);
VkFilter toVkFilter(Filter f);
VkSamplerAddressMode toVkAddress(AddressMode m);
VkBlendFactor toVkBlendFactor(BlendFactor f);
VkBlendOp toVkBlendOp(BlendOp op);
VkPrimitiveTopology toVkTopology(PrimitiveTopology t);
VkCullModeFlags toVkCull(CullMode c);
VkAttachmentLoadOp toVkLoadOp(LoadOp op);

} // namespace lpv::rhi::vk
