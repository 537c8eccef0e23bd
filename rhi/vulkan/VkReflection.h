// SPIR-V reflection through the SPIRV-Cross C API: the descriptor bindings a shader stage declares.
#pragma once

#include "VkResources.h"

#include "rhi/Device.h"
#include "rhi/Shader.h"

#include <vulkan/vulkan.h>

#include <vector>

namespace lpv::rhi::vk {

// Adds the bindings of `shader` to `bindings` (merging stage flags of a binding several stages
// share). Throws rhi::Error for what the RHI does not support: a set other than 0, arrays of
// resources, push constants, separate images/samplers, one binding number used with two types, or a
// storage image at a binding the device's Caps::storageImageBindings does not reach.
void reflectBindings(const ShaderBinary& shader, VkShaderStageFlags stage, const Caps& caps,
                     std::vector<VkDescriptorSetLayoutBinding>& bindings);

} // namespace lpv::rhi::vk
