// Reflection of descriptor bindings with spirv_cross_c.
#include "VkReflection.h"

#include "../src/DescValidation.h"

#include "rhi/Error.h"

#include <spirv_cross_c.h>

#include <memory>
#include <string>

namespace lpv::rhi::vk {
namespace {

struct ContextDeleter {
    void operator()(spvc_context_s* c) const { spvc_context_destroy(c); }
};

const char* typeName(VkDescriptorType t) {
    switch (t) {
    case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        return "uniform buffer";
    case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
        return "storage buffer";
    case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
        return "sampled texture";
    case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
        return "storage image";
    default:
        return "descriptor";
    }
}

} // namespace

void reflectBindings(const ShaderBinary& shader, VkShaderStageFlags stage, const Caps& caps,
                     std::vector<VkDescriptorSetLayoutBinding>& bindings) {
    const std::string where = "shader '" + std::string(shader.name) + "'";
    if (shader.spirv.empty()) throw Error(where + ": no SPIR-V");
    spvc_context raw = nullptr;
    if (spvc_context_create(&raw) != SPVC_SUCCESS) throw Error(where + ": spvc_context_create failed");
    std::unique_ptr<spvc_context_s, ContextDeleter> context(raw);

    spvc_parsed_ir ir = nullptr;
    spvc_compiler compiler = nullptr;
    spvc_resources resources = nullptr;
    if (spvc_context_parse_spirv(raw, shader.spirv.data(), shader.spirv.size(), &ir) != SPVC_SUCCESS ||
        spvc_context_create_compiler(raw, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &compiler) != SPVC_SUCCESS ||
        spvc_compiler_create_shader_resources(compiler, &resources) != SPVC_SUCCESS)
        throw Error(where + ": SPIR-V reflection failed: " + spvc_context_get_last_error_string(raw));

    auto expectNone = [&](spvc_resource_type type, const char* what) {
        const spvc_reflected_resource* list = nullptr;
        size_t count = 0;
        spvc_resources_get_resource_list_for_type(resources, type, &list, &count);
        if (count > 0)
            throw Error(where + ": " + what + " ('" + list[0].name + "') are not supported by the RHI");
    };
    expectNone(SPVC_RESOURCE_TYPE_PUSH_CONSTANT, "push constants (use pushUniforms)");
    expectNone(SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, "separate images (use combined samplers)");
    expectNone(SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS, "separate samplers (use combined samplers)");

    const struct {
        spvc_resource_type type;
        VkDescriptorType descriptor;
    } kinds[] = {
        {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
        {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
        {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
        {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
    };
    for (const auto& kind : kinds) {
        const spvc_reflected_resource* list = nullptr;
        size_t count = 0;
        spvc_resources_get_resource_list_for_type(resources, kind.type, &list, &count);
        for (size_t i = 0; i < count; ++i) {
            const spvc_reflected_resource& r = list[i];
            const unsigned set = spvc_compiler_get_decoration(compiler, r.id, SpvDecorationDescriptorSet);
            const unsigned binding = spvc_compiler_get_decoration(compiler, r.id, SpvDecorationBinding);
            const std::string name = where + ": '" + r.name + "' (binding " + std::to_string(binding) + ")";
            if (set != 0)
                throw Error(name + " is in descriptor set " + std::to_string(set) +
                            "; the RHI uses set 0 only");
            spvc_type type = spvc_compiler_get_type_handle(compiler, r.type_id);
            if (spvc_type_get_num_array_dimensions(type) > 0)
                throw Error(name + " is an array of resources; the RHI binds single resources");
            if (kind.type == SPVC_RESOURCE_TYPE_STORAGE_IMAGE)
                validateStorageImageBinding(binding, caps, name);
            bool merged = false;
            for (auto& b : bindings) {
                if (b.binding != binding) continue;
                if (b.descriptorType != kind.descriptor)
                    throw Error(name + " is a " + typeName(kind.descriptor) +
                                " but another stage uses binding " + std::to_string(binding) + " as a " +
                                typeName(b.descriptorType));
                b.stageFlags |= stage;
                merged = true;
            }
            if (!merged) bindings.push_back({binding, kind.descriptor, 1, stage, nullptr});
        }
    }
}

} // namespace lpv::rhi::vk
