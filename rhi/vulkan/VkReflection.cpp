// Descriptor bindings from the RHI's shader reflection (ShaderBindings.h).
#include "VkReflection.h"

#include "../src/ShaderBindings.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::vk {

VkDescriptorType descriptorType(BindingKind kind) {
    switch (kind) {
    case BindingKind::UniformBuffer:
        return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    case BindingKind::StorageBuffer:
        return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    case BindingKind::Texture:
        return VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    case BindingKind::StorageImage:
        return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    }
    return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
}

void reflectBindings(const ShaderBinary& shader, VkShaderStageFlags stage, const Caps& caps,
                     std::vector<VkDescriptorSetLayoutBinding>& bindings,
                     std::vector<ShaderBinding>& merged) {
    const std::vector<ShaderBinding> own = reflectShaderBindings(shader, caps);
    mergeShaderBindings(merged, own, "shader '" + std::string(shader.name) + "'");
    for (const ShaderBinding& s : own) {
        const VkDescriptorType type = descriptorType(s.kind);
        bool found = false;
        for (VkDescriptorSetLayoutBinding& b : bindings)
            if (b.binding == s.binding) {
                b.stageFlags |= stage; // the kinds agree: mergeShaderBindings checked
                found = true;
            }
        if (!found) bindings.push_back({s.binding, type, 1, stage, nullptr});
    }
}

} // namespace lpv::rhi::vk
