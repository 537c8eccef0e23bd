// Enum translations RHI -> Vulkan.
#include "VkFormats.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::vk {

VkFormat toVkFormat(Format f) {
    switch (f) {
    case Format::RGBA8Unorm:
        return VK_FORMAT_R8G8B8A8_UNORM;
    case Format::RGBA8Srgb:
        return VK_FORMAT_R8G8B8A8_SRGB;
    case Format::RGBA16F:
        return VK_FORMAT_R16G16B16A16_SFLOAT;
    case Format::RGBA32F:
        return VK_FORMAT_R32G32B32A32_SFLOAT;
    case Format::RG16F:
        return VK_FORMAT_R16G16_SFLOAT;
    case Format::R32F:
        return VK_FORMAT_R32_SFLOAT;
    case Format::R32UI:
        return VK_FORMAT_R32_UINT;
    case Format::RG32UI:
        return VK_FORMAT_R32G32_UINT;
    case Format::RGBA32UI:
        return VK_FORMAT_R32G32B32A32_UINT;
    case Format::D32F:
        return VK_FORMAT_D32_SFLOAT;
    case Format::D32FS8:
        return VK_FORMAT_D32_SFLOAT_S8_UINT;
    case Format::Undefined:
        return VK_FORMAT_UNDEFINED;
    }
    return VK_FORMAT_UNDEFINED;
}

VkFormat toVkFormat(VertexFormat f) {
    switch (f) {
    case VertexFormat::Float1:
        return VK_FORMAT_R32_SFLOAT;
    case VertexFormat::Float2:
        return VK_FORMAT_R32G32_SFLOAT;
    case VertexFormat::Float3:
        return VK_FORMAT_R32G32B32_SFLOAT;
    case VertexFormat::Float4:
        return VK_FORMAT_R32G32B32A32_SFLOAT;
    case VertexFormat::UByte4Norm:
        return VK_FORMAT_R8G8B8A8_UNORM;
    case VertexFormat::UInt1:
        return VK_FORMAT_R32_UINT;
    }
    return VK_FORMAT_UNDEFINED;
}

VkImageAspectFlags aspectOf(Format f) {
    if (hasStencil(f)) return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    return isDepthFormat(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

VkImageUsageFlags toVkImageUsage(uint32_t usage, Format f) {
    // Every image can be a transfer source and destination: clears, uploads, readback, copies and
    // the blit to the swapchain all need it, and it costs nothing on the drivers we run on.
    VkImageUsageFlags u = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (usage & kTextureSampled) u |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (usage & kTextureStorage) u |= VK_IMAGE_USAGE_STORAGE_BIT;
    if ((usage & kTextureColorTarget) && !isDepthFormat(f)) u |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if ((usage & kTextureDepthTarget) || ((usage & kTextureColorTarget) && isDepthFormat(f)))
        u |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    return u;
}

VkBufferUsageFlags toVkBufferUsage(uint32_t usage) {
    VkBufferUsageFlags u = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (usage & kBufferVertex) u |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    if (usage & kBufferIndex) u |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    if (usage & kBufferUniform) u |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    if (usage & kBufferStorage) u |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (usage & kBufferIndirect) u |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    return u;
}

VkImageLayout homeLayout(uint32_t usage, Format f) {
    if (usage & kTextureStorage) return VK_IMAGE_LAYOUT_GENERAL;
    if (usage & kTextureSampled) return VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    if (isDepthFormat(f) && (usage & (kTextureDepthTarget | kTextureColorTarget)))
        return VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    if (usage & kTextureColorTarget) return VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    return VK_IMAGE_LAYOUT_GENERAL; // transfer only
}

VkCompareOp toVkCompare(CompareOp op) {
    switch (op) {
    case CompareOp::Never:
        return VK_COMPARE_OP_NEVER;
    case CompareOp::Less:
        return VK_COMPARE_OP_LESS;
    case CompareOp::LessOrEqual:
        return VK_COMPARE_OP_LESS_OR_EQUAL;
    case CompareOp::Greater:
        return VK_COMPARE_OP_GREATER;
    case CompareOp::GreaterOrEqual:
        return VK_COMPARE_OP_GREATER_OR_EQUAL;
    case CompareOp::Equal:
        return VK_COMPARE_OP_EQUAL;
    case CompareOp::Always:
        return VK_COMPARE_OP_ALWAYS;
    }
    return VK_COMPARE_OP_ALWAYS;
}

VkFilter toVkFilter(Filter f) {
    return f == Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
}

VkSamplerAddressMode toVkAddress(AddressMode m) {
    switch (m) {
    case AddressMode::ClampToEdge:
        return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case AddressMode::Repeat:
        return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    case AddressMode::ClampToBorderWhite:
        return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    }
    return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}

VkBlendFactor toVkBlendFactor(BlendFactor f) {
    switch (f) {
    case BlendFactor::Zero:
        return VK_BLEND_FACTOR_ZERO;
    case BlendFactor::One:
        return VK_BLEND_FACTOR_ONE;
    case BlendFactor::SrcAlpha:
        return VK_BLEND_FACTOR_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha:
        return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstAlpha:
        return VK_BLEND_FACTOR_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha:
        return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
    }
    return VK_BLEND_FACTOR_ONE;
}

VkBlendOp toVkBlendOp(BlendOp op) {
    return op == BlendOp::Max ? VK_BLEND_OP_MAX : VK_BLEND_OP_ADD;
}

VkPrimitiveTopology toVkTopology(PrimitiveTopology t) {
    switch (t) {
    case PrimitiveTopology::TriangleList:
        return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    case PrimitiveTopology::TriangleStrip:
        return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
    case PrimitiveTopology::LineList:
        return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
    case PrimitiveTopology::PointList:
        return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    }
    return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
}

VkCullModeFlags toVkCull(CullMode c) {
    switch (c) {
    case CullMode::None:
        return VK_CULL_MODE_NONE;
    case CullMode::Front:
        return VK_CULL_MODE_FRONT_BIT;
    case CullMode::Back:
        return VK_CULL_MODE_BACK_BIT;
    }
    return VK_CULL_MODE_NONE;
}

VkAttachmentLoadOp toVkLoadOp(LoadOp op) {
    switch (op) {
    case LoadOp::Load:
        return VK_ATTACHMENT_LOAD_OP_LOAD;
    case LoadOp::Clear:
        return VK_ATTACHMENT_LOAD_OP_CLEAR;
    case LoadOp::DontCare:
        return VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    }
    return VK_ATTACHMENT_LOAD_OP_LOAD;
}

} // namespace lpv::rhi::vk
