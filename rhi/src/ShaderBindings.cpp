// Reflection of a shader's bindings with spirv_cross_c.
#include "ShaderBindings.h"

#include "DescValidation.h"

#include "rhi/Error.h"

#include <spirv_cross_c.h>

#include <memory>
#include <string>

namespace lpv::rhi {
namespace {

struct ContextDeleter {
    void operator()(spvc_context_s* c) const { spvc_context_destroy(c); }
};

// glslang decorates a readonly image variable NonWritable, and a readonly buffer's members.
bool declaredReadonly(spvc_compiler compiler, const spvc_reflected_resource& r, BindingKind kind) {
    if (spvc_compiler_has_decoration(compiler, r.id, SpvDecorationNonWritable)) return true;
    if (kind != BindingKind::StorageBuffer) return false;
    spvc_type block = spvc_compiler_get_type_handle(compiler, r.base_type_id);
    const unsigned members = spvc_type_get_num_member_types(block);
    for (unsigned m = 0; m < members; ++m)
        if (!spvc_compiler_has_member_decoration(compiler, r.base_type_id, m, SpvDecorationNonWritable))
            return false;
    return members > 0;
}

} // namespace

const char* bindingKindName(BindingKind kind) {
    switch (kind) {
    case BindingKind::UniformBuffer:
        return "uniform buffer";
    case BindingKind::StorageBuffer:
        return "storage buffer";
    case BindingKind::Texture:
        return "sampled texture";
    case BindingKind::StorageImage:
        return "storage image";
    }
    return "binding";
}

std::vector<ShaderBinding> reflectShaderBindings(const ShaderBinary& shader, const Caps& caps) {
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
        BindingKind kind;
    } kinds[] = {
        {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, BindingKind::UniformBuffer},
        {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, BindingKind::StorageBuffer},
        {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, BindingKind::Texture},
        {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, BindingKind::StorageImage},
    };
    std::vector<ShaderBinding> out;
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
            const bool storage =
                kind.kind == BindingKind::StorageBuffer || kind.kind == BindingKind::StorageImage;
            const ShaderBinding b{binding, kind.kind, storage && !declaredReadonly(compiler, r, kind.kind)};
            mergeShaderBindings(out, {b}, where);
        }
    }
    return out;
}

void mergeShaderBindings(std::vector<ShaderBinding>& into, const std::vector<ShaderBinding>& more,
                         const std::string& pipeline) {
    for (const ShaderBinding& m : more) {
        bool merged = false;
        for (ShaderBinding& b : into) {
            if (b.binding != m.binding) continue;
            if (b.kind != m.kind)
                throw Error(pipeline + ": binding " + std::to_string(m.binding) + " is used as a " +
                            bindingKindName(m.kind) + " and as a " + bindingKindName(b.kind));
            b.writable = b.writable || m.writable;
            merged = true;
        }
        if (!merged) into.push_back(m);
    }
}

} // namespace lpv::rhi
