// Creation and destruction of buffers, textures, samplers and pipelines. Each buffer and image has
// its own dedicated VkDeviceMemory: the engine makes few, large resources.
#include "../src/DescValidation.h"
#include "VkCheck.h"
#include "VkFormats.h"
#include "VkPipelines.h"
#include "VulkanDevice.h"

#include <algorithm>
#include <cstring>

namespace lpv::rhi::vk {
namespace {

VkImageViewType viewTypeOf(TextureKind kind) {
    switch (kind) {
    case TextureKind::Tex2D:
        return VK_IMAGE_VIEW_TYPE_2D;
    case TextureKind::Tex2DArray:
        return VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    case TextureKind::Tex3D:
        return VK_IMAGE_VIEW_TYPE_3D;
    }
    return VK_IMAGE_VIEW_TYPE_2D;
}

std::string usageNames(uint32_t usage) {
    std::string s;
    const std::pair<uint32_t, const char*> names[] = {{kTextureSampled, "sampled"},
                                                      {kTextureStorage, "storage"},
                                                      {kTextureColorTarget, "color target"},
                                                      {kTextureDepthTarget, "depth target"},
                                                      {kTextureTransfer, "transfer"}};
    for (const auto& [bit, name] : names)
        if (usage & bit) s += (s.empty() ? "" : "|") + std::string(name);
    return s.empty() ? "none" : s;
}

} // namespace

VulkanBuffer VulkanDevice::createBufferObject(uint64_t size, VkBufferUsageFlags usage, bool hostVisible,
                                              const std::string& name, bool hostReads) {
    const VkDevice device = ctx_->device;
    VulkanBuffer b;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    vkCheck(vkCreateBuffer(device, &info, nullptr, &b.buffer), "vkCreateBuffer");
    try {
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, b.buffer, &req);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        const VkMemoryPropertyFlags host =
            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        // The CPU reads a HostRead buffer: cached memory where there is some, uncached reads are slow.
        const VkMemoryPropertyFlags wanted = hostReads ? host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT : host;
        alloc.memoryTypeIndex =
            hostVisible ? ctx_->memoryType(req.memoryTypeBits, wanted, host)
                        : ctx_->memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        vkCheck(vkAllocateMemory(device, &alloc, nullptr, &b.memory), "vkAllocateMemory (buffer)");
        vkCheck(vkBindBufferMemory(device, b.buffer, b.memory, 0), "vkBindBufferMemory");
        if (hostVisible)
            vkCheck(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
        b.bytes = req.size;
    } catch (...) {
        destroyBufferObject(b);
        throw;
    }
    b.desc.size = size;
    b.desc.debugName = name;
    ctx_->name(VK_OBJECT_TYPE_BUFFER, b.buffer, name);
    ctx_->name(VK_OBJECT_TYPE_DEVICE_MEMORY, b.memory, name + " memory");
    return b;
}

void VulkanDevice::destroyBufferObject(VulkanBuffer& b) {
    const VkDevice device = ctx_->device;
    if (b.buffer) vkDestroyBuffer(device, b.buffer, nullptr);
    if (b.memory) vkFreeMemory(device, b.memory, nullptr); // unmaps implicitly
    b.buffer = VK_NULL_HANDLE;
    b.memory = VK_NULL_HANDLE;
    b.mapped = nullptr;
}

void VulkanDevice::destroyTextureObject(VulkanTexture& t) {
    const VkDevice device = ctx_->device;
    for (VkImageView v : t.layeredViews)
        vkDestroyImageView(device, v, nullptr);
    for (VkImageView v : t.targetViews)
        vkDestroyImageView(device, v, nullptr);
    for (VkImageView v : t.mipViews)
        vkDestroyImageView(device, v, nullptr);
    if (t.sampledView) vkDestroyImageView(device, t.sampledView, nullptr);
    if (t.image) vkDestroyImage(device, t.image, nullptr);
    if (t.memory) vkFreeMemory(device, t.memory, nullptr);
    t = VulkanTexture{};
}

void VulkanDevice::destroyPipelineObject(VulkanPipeline& p) {
    destroyPipeline(ctx_->device, p);
}

BufferHandle VulkanDevice::createBuffer(const BufferDesc& desc, const void* initialData) {
    if (desc.size == 0) throw Error("buffer '" + desc.debugName + "': size is 0");
    const bool host = desc.access != MemoryAccess::GpuOnly;
    VulkanBuffer b = createBufferObject(desc.size, toVkBufferUsage(desc.usage), host, desc.debugName,
                                        desc.access == MemoryAccess::HostRead);
    b.desc = desc;
    if (initialData && host) std::memcpy(b.mapped, initialData, desc.size);
    const BufferHandle h = buffers.insert(b);
    allocations_.add(ResourceType::Buffer, h.bits,
                     {ResourceType::Buffer, desc.debugName, desc.category, b.bytes});
    if (initialData && !host) {
        try {
            // Legal inside a frame too: the immediate submission runs before the frame's commands,
            // which cannot have used a buffer that did not exist yet.
            copyIntoBuffer(buffers.get(h), 0, initialData, desc.size);
        } catch (...) {
            destroy(h);
            throw;
        }
    }
    return h;
}

TextureHandle VulkanDevice::createTexture(const TextureDesc& desc) {
    validateTextureDesc(desc, caps_);
    const std::string where = "texture '" + desc.debugName + "'";
    if (desc.mipLevels > 16) throw Error(where + ": more than 16 mip levels");

    const VkDevice device = ctx_->device;
    VulkanTexture t;
    t.desc = desc;
    t.aspect = aspectOf(desc.format);
    t.home = unifiedImageLayouts_ ? VK_IMAGE_LAYOUT_GENERAL : homeLayout(desc.usage, desc.format);
    t.layouts.assign(desc.mipLevels, VK_IMAGE_LAYOUT_UNDEFINED);

    const bool renderable = desc.usage & (kTextureColorTarget | kTextureDepthTarget);
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = desc.kind == TextureKind::Tex3D ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    // Rendering into one slice of a volume needs 2D views of the 3D image.
    if (desc.kind == TextureKind::Tex3D && renderable) info.flags |= VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
    info.format = toVkFormat(desc.format);
    info.extent = {desc.width, desc.height, desc.kind == TextureKind::Tex3D ? desc.depthOrLayers : 1};
    info.mipLevels = desc.mipLevels;
    info.arrayLayers = t.arrayLayers();
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = toVkImageUsage(desc.usage, desc.format);
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;

    // A readable error instead of a validation message when the device cannot do what is asked.
    VkImageFormatProperties formatProps;
    const VkResult supported = vkGetPhysicalDeviceImageFormatProperties(
        ctx_->physical, info.format, info.imageType, info.tiling, info.usage, info.flags, &formatProps);
    if (supported != VK_SUCCESS)
        throw Error(where + ": " + std::string(formatName(desc.format)) + " " +
                    (desc.kind == TextureKind::Tex3D ? "3D" : "2D") + " textures with usage " +
                    usageNames(desc.usage) + " are not supported by this device");
    if (info.extent.width > formatProps.maxExtent.width ||
        info.extent.height > formatProps.maxExtent.height ||
        info.extent.depth > formatProps.maxExtent.depth || info.arrayLayers > formatProps.maxArrayLayers)
        throw Error(where + ": " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + "x" +
                    std::to_string(desc.depthOrLayers) + " exceeds the device's limits for this format");

    vkCheck(vkCreateImage(device, &info, nullptr, &t.image), "vkCreateImage");
    try {
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device, t.image, &req);
        VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = ctx_->memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
        vkCheck(vkAllocateMemory(device, &alloc, nullptr, &t.memory), "vkAllocateMemory (image)");
        vkCheck(vkBindImageMemory(device, t.image, t.memory, 0), "vkBindImageMemory");
        t.bytes = req.size;
        ctx_->name(VK_OBJECT_TYPE_IMAGE, t.image, desc.debugName);
        ctx_->name(VK_OBJECT_TYPE_DEVICE_MEMORY, t.memory, desc.debugName + " memory");

        auto makeView = [&](VkImageViewType type, VkImageSubresourceRange range, VkImageUsageFlags usage,
                            const std::string& name) {
            VkImageViewUsageCreateInfo usageInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
            usageInfo.usage = usage;
            VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO, &usageInfo};
            vi.image = t.image;
            vi.viewType = type;
            vi.format = info.format;
            vi.subresourceRange = range;
            VkImageView view = VK_NULL_HANDLE;
            vkCheck(vkCreateImageView(device, &vi, nullptr, &view), "vkCreateImageView");
            ctx_->name(VK_OBJECT_TYPE_IMAGE_VIEW, view, name);
            return view;
        };
        const VkImageViewType fullType = viewTypeOf(desc.kind);
        if (desc.usage & kTextureSampled)
            t.sampledView = makeView(fullType, {t.aspect, 0, desc.mipLevels, 0, t.arrayLayers()},
                                     VK_IMAGE_USAGE_SAMPLED_BIT, desc.debugName + " sampled");
        if (desc.usage & kTextureStorage)
            for (uint32_t mip = 0; mip < desc.mipLevels; ++mip)
                t.mipViews.push_back(makeView(fullType, {t.aspect, mip, 1, 0, t.arrayLayers()},
                                              VK_IMAGE_USAGE_STORAGE_BIT,
                                              desc.debugName + " storage mip " + std::to_string(mip)));
        if (renderable) {
            // One 2D view per render target a pass can select: (mip, layer) or (mip, 3D slice).
            const VkImageUsageFlags attachment = isDepthFormat(desc.format)
                                                     ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                     : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
            for (uint32_t mip = 0; mip < desc.mipLevels; ++mip) {
                t.targetBase.push_back(uint32_t(t.targetViews.size()));
                for (uint32_t layer = 0; layer < t.targetLayers(mip); ++layer)
                    t.targetViews.push_back(makeView(VK_IMAGE_VIEW_TYPE_2D, {t.aspect, mip, 1, layer, 1},
                                                     attachment,
                                                     desc.debugName + " target mip " + std::to_string(mip) +
                                                         " layer " + std::to_string(layer)));
                if (desc.kind != TextureKind::Tex2D && !isDepthFormat(desc.format))
                    t.layeredViews.push_back(
                        makeView(VK_IMAGE_VIEW_TYPE_2D_ARRAY, {t.aspect, mip, 1, 0, t.targetLayers(mip)},
                                 attachment, desc.debugName + " layered target mip " + std::to_string(mip)));
            }
        }
    } catch (...) {
        destroyTextureObject(t);
        throw;
    }
    const uint64_t bytes = t.bytes;
    const TextureHandle h = textures.insert(std::move(t));
    allocations_.add(ResourceType::Texture, h.bits,
                     {ResourceType::Texture, desc.debugName, desc.category, bytes});
    // Moved to its home layout by the next command buffer recorded (frame or immediate).
    newTextures_.push_back(h);
    return h;
}

SamplerHandle VulkanDevice::createSampler(const SamplerDesc& desc) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = toVkFilter(desc.magFilter);
    info.minFilter = toVkFilter(desc.minFilter);
    info.mipmapMode =
        desc.mipFilter == Filter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = toVkAddress(desc.address);
    info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    if (desc.maxAnisotropy > 1.0f && ctx_->samplerAnisotropy) {
        info.anisotropyEnable = VK_TRUE;
        info.maxAnisotropy = std::min(desc.maxAnisotropy, ctx_->properties.limits.maxSamplerAnisotropy);
    }
    info.compareEnable = desc.compareEnable ? VK_TRUE : VK_FALSE;
    info.compareOp = toVkCompare(desc.compareOp);
    info.minLod = 0.0f;
    info.maxLod = VK_LOD_CLAMP_NONE;
    VulkanSampler s{desc, VK_NULL_HANDLE};
    vkCheck(vkCreateSampler(ctx_->device, &info, nullptr, &s.sampler), "vkCreateSampler");
    ctx_->name(VK_OBJECT_TYPE_SAMPLER, s.sampler, desc.debugName);
    return samplers.insert(std::move(s));
}

GraphicsPipelineHandle VulkanDevice::createPipeline(const GraphicsPipelineDesc& desc) {
    return graphicsPipelines.insert(buildGraphicsPipeline(*ctx_, caps_, desc));
}

ComputePipelineHandle VulkanDevice::createPipeline(const ComputePipelineDesc& desc) {
    return computePipelines.insert(buildComputePipeline(*ctx_, caps_, desc));
}

void VulkanDevice::destroy(BufferHandle h) {
    VulkanBuffer b = buffers.remove(h);
    allocations_.remove(ResourceType::Buffer, h.bits);
    retire([this, b]() mutable { destroyBufferObject(b); });
}

void VulkanDevice::destroy(TextureHandle h) {
    VulkanTexture t = textures.remove(h);
    allocations_.remove(ResourceType::Texture, h.bits);
    std::erase(newTextures_, h);
    retire([this, t = std::move(t)]() mutable { destroyTextureObject(t); });
}

void VulkanDevice::destroy(SamplerHandle h) {
    const VkSampler s = samplers.remove(h).sampler;
    retire([this, s] { vkDestroySampler(ctx_->device, s, nullptr); });
}

void VulkanDevice::destroy(GraphicsPipelineHandle h) {
    VulkanPipeline p = graphicsPipelines.remove(h);
    retire([this, p]() mutable { destroyPipelineObject(p); });
}

void VulkanDevice::destroy(ComputePipelineHandle h) {
    VulkanPipeline p = computePipelines.remove(h);
    retire([this, p]() mutable { destroyPipelineObject(p); });
}

void* VulkanDevice::mapped(BufferHandle h) {
    VulkanBuffer& b = buffers.get(h);
    if (b.desc.access == MemoryAccess::GpuOnly)
        throw Error("buffer '" + b.desc.debugName + "' is not MemoryAccess::HostWrite or HostRead");
    return b.mapped;
}

} // namespace lpv::rhi::vk
