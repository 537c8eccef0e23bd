// The resources a shader declares, read from its SPIR-V with SPIRV-Cross: both backends bind by
// these (Vulkan builds its descriptor layouts from them) and track hazards by them (which bound
// resources a command reads and which it may write).
#pragma once

#include "rhi/Device.h"
#include "rhi/Shader.h"

#include <cstdint>
#include <vector>

namespace lpv::rhi {

enum class BindingKind : uint8_t { UniformBuffer, StorageBuffer, Texture, StorageImage };

struct ShaderBinding {
    uint32_t binding = 0;
    BindingKind kind = BindingKind::UniformBuffer;
    // A storage image or buffer the shader may store to (not declared readonly).
    bool writable = false;
};

// The bindings `shader` declares, one per binding number. Throws rhi::Error for what the RHI does
// not support: a set other than 0, arrays of resources, push constants, separate images/samplers,
// or a storage image at a binding the device's Caps::storageImageBindings does not reach.
std::vector<ShaderBinding> reflectShaderBindings(const ShaderBinary& shader, const Caps& caps);

// Adds `more` to `into`, one entry per binding number (a writable one stays writable); throws
// rhi::Error, naming `pipeline`, where two stages use one binding as two kinds.
void mergeShaderBindings(std::vector<ShaderBinding>& into, const std::vector<ShaderBinding>& more,
                         const std::string& pipeline);

const char* bindingKindName(BindingKind kind);

} // namespace lpv::rhi
