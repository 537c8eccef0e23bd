// What the Vulkan backend keeps per buffer, texture, sampler and pipeline behind the handles.
#pragma once

#include "rhi/Pipeline.h"
#include "rhi/Resources.h"

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace lpv::rhi::vk {

struct VulkanBuffer {
    BufferDesc desc;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr; // host-visible buffers stay mapped for their whole life
    uint64_t bytes = 0;     // what the driver allocated
};

struct VulkanTexture {
    TextureDesc desc;
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    uint64_t bytes = 0;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageLayout home = VK_IMAGE_LAYOUT_GENERAL;
    // Current layout of each mip level, in recording order. All layers/slices of a mip share it.
    std::vector<VkImageLayout> layouts;
    VkImageView sampledView = VK_NULL_HANDLE; // all mips and layers: sampling
    std::vector<VkImageView> mipViews;        // one mip, all layers: storage images
    // One 2D view per (mip, layer or 3D slice) for render targets; targetBase[mip] indexes the
    // first view of that mip.
    std::vector<VkImageView> targetViews;
    std::vector<uint32_t> targetBase;
    // Array and 3D colour targets: one 2D-array view per mip over every layer or slice, for
    // layered passes (ColorAttachment::layered).
    std::vector<VkImageView> layeredViews;

    uint32_t arrayLayers() const { return desc.kind == TextureKind::Tex2DArray ? desc.depthOrLayers : 1; }
    uint32_t width(uint32_t mip) const { return desc.width >> mip ? desc.width >> mip : 1; }
    uint32_t height(uint32_t mip) const { return desc.height >> mip ? desc.height >> mip : 1; }
    // Depth of a mip for 3D textures (1 otherwise).
    uint32_t depth(uint32_t mip) const {
        if (desc.kind != TextureKind::Tex3D) return 1;
        return desc.depthOrLayers >> mip ? desc.depthOrLayers >> mip : 1;
    }
    // Layers (array) or slices (3D) a render target of this mip can select.
    uint32_t targetLayers(uint32_t mip) const {
        return desc.kind == TextureKind::Tex3D ? depth(mip) : arrayLayers();
    }
};

struct VulkanSampler {
    SamplerDesc desc;
    VkSampler sampler = VK_NULL_HANDLE;
};

// One resource binding a pipeline declares (set 0), found by reflecting its SPIR-V.
struct PipelineBinding {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    bool writable = false; // a storage image or buffer not declared readonly
};

struct VulkanPipeline {
    std::string name;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    uint32_t pointChunk = 0; // > 0: draw() issues a point list in draws of at most this many points
    std::vector<PipelineBinding> bindings;
};

} // namespace lpv::rhi::vk
