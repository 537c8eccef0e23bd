// Immediate transfers (uploads and readbacks): recorded into a separate command buffer, submitted
// and waited for at once, through one host-visible staging buffer that grows on demand.
#include "VkBarriers.h"
#include "VkCheck.h"
#include "VulkanDevice.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace lpv::rhi::vk {
namespace {

constexpr uint32_t kStagingRecordKey = 2; // allocation-record key (generation 0: not a handle)

} // namespace

void VulkanDevice::checkImmediate(const char* what) const {
    if (inFrame_)
        throw Error(std::string(what) +
                    " inside beginFrame()/endFrame(): immediate transfers wait for the GPU; "
                    "call it between frames");
}

VkCommandBuffer VulkanDevice::beginImmediate(const char* what) {
    vkCheck(vkResetCommandPool(ctx_->device, immediatePool_, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(immediateCmd_, &begin), "vkBeginCommandBuffer");
    if (ctx_->cmdBeginDebugUtilsLabel) {
        VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
        label.pLabelName = what;
        ctx_->cmdBeginDebugUtilsLabel(immediateCmd_, &label);
    }
    // Ordered after every frame submitted before (the queue gives no memory ordering by itself).
    fullBarrier(immediateCmd_);
    // Between frames this is the next command buffer to run; inside one, the frame's is.
    if (!inFrame_) flushNewTextures(immediateCmd_);
    return immediateCmd_;
}

void VulkanDevice::submitImmediate() {
    fullBarrier(immediateCmd_);
    if (ctx_->cmdEndDebugUtilsLabel) ctx_->cmdEndDebugUtilsLabel(immediateCmd_);
    vkCheck(vkEndCommandBuffer(immediateCmd_), "vkEndCommandBuffer");
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = immediateCmd_;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    vkCheck(vkResetFences(ctx_->device, 1, &immediateFence_), "vkResetFences");
    vkCheck(vkQueueSubmit2(ctx_->queue, 1, &submit, immediateFence_), "vkQueueSubmit2");
    vkCheck(vkWaitForFences(ctx_->device, 1, &immediateFence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    // A fence also covers everything submitted earlier on the queue: all frames are done.
    markAllComplete();
    collectGarbage();
}

void VulkanDevice::ensureStaging(uint64_t size) {
    if (staging_.buffer && staging_.desc.size >= size) return;
    if (staging_.buffer) {
        destroyBufferObject(staging_); // only immediate transfers use it, and they have finished
        allocations_.remove(ResourceType::Buffer, kStagingRecordKey);
    }
    const uint64_t bytes = std::bit_ceil(std::max<uint64_t>(size, 1u << 20));
    staging_ = createBufferObject(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  true, "staging");
    allocations_.add(ResourceType::Buffer, kStagingRecordKey,
                     {ResourceType::Buffer, "staging", "rhi.internal", staging_.bytes});
}

void VulkanDevice::copyIntoBuffer(VulkanBuffer& b, uint64_t offset, const void* data, uint64_t size) {
    ensureStaging(size);
    std::memcpy(staging_.mapped, data, size);
    const VkCommandBuffer cmd = beginImmediate("upload buffer");
    const VkBufferCopy region{0, offset, size};
    vkCmdCopyBuffer(cmd, staging_.buffer, b.buffer, 1, &region);
    submitImmediate();
}

void VulkanDevice::checkTextureRange(const VulkanTexture& t, uint32_t mip, uint64_t size,
                                     const char* what) const {
    if (mip >= t.desc.mipLevels)
        throw Error(std::string(what) + " '" + t.desc.debugName + "': no mip " + std::to_string(mip));
    const uint64_t expected = uint64_t(t.width(mip)) * t.height(mip) * t.depth(mip) * t.arrayLayers() *
                              bytesPerPixel(t.desc.format);
    if (size != expected)
        throw Error(std::string(what) + " '" + t.desc.debugName + "' mip " + std::to_string(mip) + ": " +
                    std::to_string(size) + " bytes given, " + std::to_string(expected) +
                    " expected (tightly packed)");
}

void VulkanDevice::uploadBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) {
    checkImmediate("uploadBuffer");
    VulkanBuffer& b = buffers.get(h);
    if (offset + size > b.desc.size)
        throw Error("uploadBuffer '" + b.desc.debugName + "': range [" + std::to_string(offset) + ", " +
                    std::to_string(offset + size) + ") exceeds its size " + std::to_string(b.desc.size));
    if (size == 0) return;
    copyIntoBuffer(b, offset, data, size);
}

void VulkanDevice::readBuffer(BufferHandle h, uint64_t offset, void* out, uint64_t size) {
    checkImmediate("readBuffer");
    VulkanBuffer& b = buffers.get(h);
    if (offset + size > b.desc.size)
        throw Error("readBuffer '" + b.desc.debugName + "': range [" + std::to_string(offset) + ", " +
                    std::to_string(offset + size) + ") exceeds its size " + std::to_string(b.desc.size));
    if (size == 0) return;
    ensureStaging(size);
    const VkCommandBuffer cmd = beginImmediate("read buffer");
    const VkBufferCopy region{offset, 0, size};
    vkCmdCopyBuffer(cmd, b.buffer, staging_.buffer, 1, &region);
    submitImmediate();
    std::memcpy(out, staging_.mapped, size);
}

void VulkanDevice::uploadTexture(TextureHandle h, uint32_t mip, const void* data, uint64_t size) {
    checkImmediate("uploadTexture");
    checkTextureRange(textures.get(h), mip, size, "uploadTexture");
    ensureStaging(size);
    std::memcpy(staging_.mapped, data, size);
    const VkCommandBuffer cmd = beginImmediate("upload texture");
    VulkanTexture& t = textures.get(h);
    transition(cmd, t, mip, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{}; // row length and image height 0: tightly packed, layers in order
    region.imageSubresource = {t.aspect, mip, 0, t.arrayLayers()};
    region.imageExtent = {t.width(mip), t.height(mip), t.depth(mip)};
    vkCmdCopyBufferToImage(cmd, staging_.buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transitionHome(cmd, t);
    submitImmediate();
}

void VulkanDevice::readTexture(TextureHandle h, uint32_t mip, void* out, uint64_t size) {
    checkImmediate("readTexture");
    checkTextureRange(textures.get(h), mip, size, "readTexture");
    ensureStaging(size);
    const VkCommandBuffer cmd = beginImmediate("read texture");
    VulkanTexture& t = textures.get(h);
    transition(cmd, t, mip, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {t.aspect, mip, 0, t.arrayLayers()};
    region.imageExtent = {t.width(mip), t.height(mip), t.depth(mip)};
    vkCmdCopyImageToBuffer(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging_.buffer, 1, &region);
    transitionHome(cmd, t);
    submitImmediate();
    std::memcpy(out, staging_.mapped, size);
}

} // namespace lpv::rhi::vk
