// Shared argument checks.
#include "DescValidation.h"

#include "rhi/Error.h"

#include <algorithm>
#include <string>

namespace lpv::rhi {

void validateTextureDesc(const TextureDesc& desc, const Caps& caps) {
    const std::string where = "texture '" + desc.debugName + "'";
    if (desc.width == 0 || desc.height == 0 || desc.depthOrLayers == 0) throw Error(where + ": zero extent");
    if (desc.format == Format::Undefined) throw Error(where + ": undefined format");
    if (desc.kind == TextureKind::Tex2D && desc.depthOrLayers != 1)
        throw Error(where + ": a 2D texture has depthOrLayers 1");
    uint32_t maxMips = 1;
    for (uint32_t s =
             std::max({desc.width, desc.height, desc.kind == TextureKind::Tex3D ? desc.depthOrLayers : 1u});
         s > 1; s >>= 1)
        ++maxMips;
    if (desc.mipLevels == 0 || desc.mipLevels > maxMips)
        throw Error(where + ": mipLevels " + std::to_string(desc.mipLevels) + " (1.." +
                    std::to_string(maxMips) + ")");
    const uint32_t maxExtent =
        desc.kind == TextureKind::Tex3D ? caps.max3DTextureSize : caps.max2DTextureSize;
    if (maxExtent && (desc.width > maxExtent || desc.height > maxExtent ||
                      (desc.kind == TextureKind::Tex3D && desc.depthOrLayers > maxExtent)))
        throw Error(where + ": " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + "x" +
                    std::to_string(desc.depthOrLayers) + " exceeds the device's limits");
    // A depth-stencil texture is only ever a target: sampling, storing or copying it would need
    // one of its two aspects named, which the RHI has no way to say.
    if (hasStencil(desc.format) && (desc.kind != TextureKind::Tex2D || desc.usage != kTextureDepthTarget))
        throw Error(where + ": " + std::string(formatName(desc.format)) +
                    " is a 2D depth target only (no sampling, storage or transfer)");
}

void validateStencilState(const GraphicsPipelineDesc& desc) {
    if (desc.stencil.enabled && !hasStencil(desc.depthFormat))
        throw Error("pipeline '" + desc.debugName +
                    "': a stencil test needs a depth format with a stencil, not " +
                    std::string(formatName(desc.depthFormat)));
}

bool isLayeredPass(const RenderPassDesc& desc, const Caps& caps) {
    uint32_t layered = 0;
    for (uint32_t i = 0; i < desc.colorCount && i < RenderPassDesc::kMaxColorTargets; ++i)
        layered += desc.colors[i].layered ? 1 : 0;
    if (layered == 0) return false;
    // The message is built only on failure: a valid pass allocates nothing.
    const auto fail = [&](const char* why) {
        throw Error("beginRenderPass '" + std::string(desc.debugName) + "': " + why);
    };
    if (!caps.vertexShaderLayer)
        fail("layered targets need a vertex shader that writes gl_Layer, which this device lacks "
             "(Caps::vertexShaderLayer)");
    if (layered != desc.colorCount) fail("every color target must be layered, or none");
    if (desc.depth.texture) fail("a layered pass takes no depth target");
    return true;
}

uint32_t layeredTargetLayers(const RenderPassDesc& desc, uint32_t index, const TextureDesc& texture,
                             uint32_t layers, uint32_t passLayers) {
    if (texture.kind == TextureKind::Tex2D || desc.colors[index].layer != 0)
        throw Error("beginRenderPass: texture '" + texture.debugName +
                    "' cannot be a layered target (it needs to be an array or 3D texture, from layer 0)");
    if (index > 0 && layers != passLayers)
        throw Error("beginRenderPass '" + std::string(desc.debugName) +
                    "': layered targets differ in their layer counts");
    return layers;
}

void validateStorageImageBinding(uint32_t binding, const Caps& caps, std::string_view what) {
    if (binding >= caps.storageImageBindings)
        throw Error(std::string(what) + ": storage image binding " + std::to_string(binding) +
                    " is not below " + std::to_string(caps.storageImageBindings) +
                    ", the device's Caps::storageImageBindings (OpenGL guarantees " +
                    std::to_string(kPortableStorageImageBindings) + ")");
}

uint32_t configuredStorageImageBindings(uint32_t device, std::optional<uint32_t> configured) {
    if (configured && *configured < kPortableStorageImageBindings)
        throw Error("DeviceConfig::storageImageBindings " + std::to_string(*configured) + " is below the " +
                    std::to_string(kPortableStorageImageBindings) +
                    " every OpenGL 4.5 device has, which the engine's shaders are written for");
    return std::min({device, configured.value_or(kMaxBindings), kMaxBindings});
}

void clipScissorToOrigin(int32_t& x, int32_t& y, uint32_t& width, uint32_t& height) {
    if (x < 0) {
        const uint32_t cut = uint32_t(-int64_t(x));
        width = width > cut ? width - cut : 0;
        x = 0;
    }
    if (y < 0) {
        const uint32_t cut = uint32_t(-int64_t(y));
        height = height > cut ? height - cut : 0;
        y = 0;
    }
}

void validateTextureCopyCount(size_t count) {
    if (count > TextureCopy::kMaxCopies)
        throw Error("copyTextures: " + std::to_string(count) + " copies, at most " +
                    std::to_string(TextureCopy::kMaxCopies) + " in one call");
}

void validateTextureCopy(TextureHandle src, TextureHandle dst, const TextureDesc& s, const TextureDesc& d) {
    if (src == dst) throw Error("copyTexture: source and destination are the same texture");
    if (s.kind != d.kind || s.format != d.format || s.width != d.width || s.height != d.height ||
        s.depthOrLayers != d.depthOrLayers)
        throw Error("copyTexture: '" + s.debugName + "' and '" + d.debugName +
                    "' differ in kind, format or size");
}

} // namespace lpv::rhi
