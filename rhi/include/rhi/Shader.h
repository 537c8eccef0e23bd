// A shader as the build produced it: GLSL written once (Vulkan dialect), compiled by glslang to
// SPIR-V at build time, and turned back into GLSL 4.50 by SPIRV-Cross for the OpenGL backend.
// Binding numbers in the source are the only resource namespace: a pipeline's uniform buffers,
// textures, storage images and storage buffers each use a distinct `binding`, all in set 0.
// Storage images take bindings below Caps::storageImageBindings: OpenGL binds them to image units,
// of which it guarantees 8 (NVIDIA's driver has exactly 8, Mesa 32), so a shader meant for every
// device keeps them below kPortableStorageImageBindings, and one that needs more is a variant
// chosen by that capability. Vulkan pipeline creation and every bindStorageImage enforce the
// device's limit; DeviceConfig::storageImageBindings lowers it, so tests run the narrow paths
// (and catch a shader beyond them) on any device.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace lpv::rhi {

// Every backend tracks bindings 0..kMaxBindings-1.
inline constexpr uint32_t kMaxBindings = 32;
inline constexpr uint32_t kPortableStorageImageBindings = 8;

enum class ShaderStage : uint8_t { Vertex, Fragment, Compute };

struct ShaderBinary {
    std::string_view name; // source file, for error messages and debug names
    ShaderStage stage = ShaderStage::Vertex;
    std::span<const uint32_t> spirv;
    std::string_view glsl;
};

} // namespace lpv::rhi
