// Argument checks every backend makes the same way, so misuse gives one message whatever the API.
#pragma once

#include "rhi/CommandList.h"
#include "rhi/Device.h"
#include "rhi/Pipeline.h"
#include "rhi/Shader.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace lpv::rhi {

// Throws rhi::Error naming the texture when its extent, format, kind or mip count is invalid or
// beyond the device's limits.
void validateTextureDesc(const TextureDesc& desc, const Caps& caps);

// CommandList::copyTextures' arguments: throws rhi::Error for more than TextureCopy::kMaxCopies
// copies, and naming both textures for a copy onto itself or between different kinds, formats or
// sizes. `descOf` gives a handle's desc.
template <typename DescOf> void validateTextureCopies(std::span<const TextureCopy> copies, DescOf&& descOf);
void validateTextureCopy(TextureHandle src, TextureHandle dst, const TextureDesc& s, const TextureDesc& d);
void validateTextureCopyCount(size_t count);

template <typename DescOf> void validateTextureCopies(std::span<const TextureCopy> copies, DescOf&& descOf) {
    validateTextureCopyCount(copies.size());
    for (const TextureCopy& c : copies)
        validateTextureCopy(c.src, c.dst, descOf(c.src), descOf(c.dst));
}

// Throws rhi::Error naming the pipeline when it tests the stencil without a depth format that
// has one.
void validateStencilState(const GraphicsPipelineDesc& desc);

// Whether a pass is layered (ColorAttachment::layered). Throws rhi::Error naming the pass when it
// mixes layered and single-layer targets, has a depth target, or the device lacks
// Caps::vertexShaderLayer. The backends check that the layer counts agree.
bool isLayeredPass(const RenderPassDesc& desc, const Caps& caps);

// Colour target `index` of a layered pass, `layers` layers (or slices) at its mip: throws unless it
// is an array or 3D texture bound from layer 0 with the layer count of the targets before it
// (`passLayers`). Returns the pass's layer count.
uint32_t layeredTargetLayers(const RenderPassDesc& desc, uint32_t index, const TextureDesc& texture,
                             uint32_t layers, uint32_t passLayers);

// Throws rhi::Error unless a storage image's binding is below the device's
// Caps::storageImageBindings (rhi/Shader.h).
void validateStorageImageBinding(uint32_t binding, const Caps& caps, std::string_view what);

// The device's storage image bindings as DeviceConfig::storageImageBindings lowers them (to no
// less than kPortableStorageImageBindings: throws rhi::Error), at most kMaxBindings.
uint32_t configuredStorageImageBindings(uint32_t device, std::optional<uint32_t> configured);

// Clips a scissor rectangle to the framebuffer's origin: Vulkan rejects negative offsets, and GL
// must cut the same pixels.
void clipScissorToOrigin(int32_t& x, int32_t& y, uint32_t& width, uint32_t& height);

} // namespace lpv::rhi
