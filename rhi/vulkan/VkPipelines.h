// Graphics and compute pipelines. The descriptor set layout (set 0, push descriptors) of a pipeline
// comes from reflecting the SPIR-V of all its stages, so callers never describe their bindings.
#pragma once

#include "VkContext.h"
#include "VkResources.h"

#include "rhi/Device.h"
#include "rhi/Pipeline.h"

namespace lpv::rhi::vk {

VulkanPipeline buildGraphicsPipeline(const VulkanContext& ctx, const Caps& caps,
                                     const GraphicsPipelineDesc& desc);
VulkanPipeline buildComputePipeline(const VulkanContext& ctx, const Caps& caps,
                                    const ComputePipelineDesc& desc);
void destroyPipeline(VkDevice device, VulkanPipeline& pipeline);

} // namespace lpv::rhi::vk
