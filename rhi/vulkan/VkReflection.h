// Descriptor set layout bindings from the shaders' reflected bindings (ShaderBindings.h).
#pragma once

#include "../src/ShaderBindings.h"

#include "rhi/Device.h"
#include "rhi/Shader.h"

#include <vulkan/vulkan.h>

#include <vector>

namespace lpv::rhi::vk {

VkDescriptorType descriptorType(BindingKind kind);

// Adds the bindings of `shader` to `bindings` (merging stage flags of a binding several stages
// share) and to `merged` (what the pipeline's commands access). Throws rhi::Error for what the RHI
// does not support (reflectShaderBindings) or for one binding number used with two types.
void reflectBindings(const ShaderBinary& shader, VkShaderStageFlags stage, const Caps& caps,
                     std::vector<VkDescriptorSetLayoutBinding>& bindings, std::vector<ShaderBinding>& merged);

} // namespace lpv::rhi::vk
