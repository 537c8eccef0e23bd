// The Vulkan device: creation, frames in flight, presentation, timestamps and deferred release.
// Resource creation lives in VkDeviceResources.cpp, immediate transfers in VkTransfers.cpp.
#include "VulkanDevice.h"
#include "../src/DescValidation.h"

#include "VkBarriers.h"
#include "VkCheck.h"

#include "../src/BackendFactory.h"
#include "../src/CpuRasterizer.h"

#include "platforms/Log.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace lpv::rhi::vk {
namespace {

// Allocation-record keys of internal buffers (generation 0: never a real handle).
constexpr uint32_t kRingRecordKey = 1;

const char* deviceTypeName(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
        return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
        return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
        return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
        return "CPU";
    default:
        return "other";
    }
}

} // namespace

VulkanDevice::VulkanDevice(const DeviceConfig& config) : config_(config) {
    const char* env = std::getenv("LPV_CONSERVATIVE_BARRIERS");
    conservativeBarriers_ = config.conservativeBarriers || (env && env[0] == '1');
    if (config.framesInFlight == 0) throw Error("DeviceConfig::framesInFlight must be at least 1");
    ctx_ = std::make_unique<VulkanContext>(config); // throws BackendUnavailable with the reason
    unifiedImageLayouts_ = config.unifiedImageLayouts.value_or(ctx_->unifiedImageLayouts);
    try {
        const VkPhysicalDeviceLimits& limits = ctx_->properties.limits;
        caps_.deviceName = ctx_->properties.deviceName;
        caps_.driverName = ctx_->driverName;
        const bool timestamps = limits.timestampComputeAndGraphics && ctx_->timestampValidBits > 0;
        caps_.timestampSource = timestamps ? TimestampSource::GpuQueries : TimestampSource::None;
        caps_.maxTimestampsPerFrame = config.maxTimestampsPerFrame;
        caps_.framesInFlight = config.framesInFlight;
        caps_.max3DTextureSize = limits.maxImageDimension3D;
        caps_.max2DTextureSize = limits.maxImageDimension2D;
        caps_.maxColorTargets = std::min(limits.maxColorAttachments, RenderPassDesc::kMaxColorTargets);
        caps_.presentation = config.window != nullptr;
        caps_.vertexShaderLayer = ctx_->shaderOutputLayer && config.vertexShaderLayer;
        if (ctx_->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU)
            caps_.concurrentWorkgroups = cpuRasterizerThreads();
        caps_.maskedBranches =
            config.maskedBranches.value_or(ctx_->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU);
        caps_.shaderStencilExport = ctx_->shaderStencilExport;
        caps_.multiDrawIndirect = ctx_->multiDrawIndirect && config.multiDrawIndirect.value_or(true);
        caps_.fragmentStores = ctx_->fragmentStores;
        caps_.storageImageBindings = configuredStorageImageBindings(limits.maxPerStageDescriptorStorageImages,
                                                                    config.storageImageBindings);
        caps_.fragmentTextureBindings =
            std::min({limits.maxPerStageDescriptorSamplers, limits.maxPerStageDescriptorSampledImages,
                      config.fragmentTextureBindings.value_or(kMaxBindings), kMaxBindings});
        caps_.computeTextureBindings = std::min(
            {limits.maxPerStageDescriptorSamplers, limits.maxPerStageDescriptorSampledImages, kMaxBindings});

        timestamps_.create(*ctx_, timestamps, config.framesInFlight + 1, config.maxTimestampsPerFrame);
        createFrames();

        ringAlignment_ = std::max<uint64_t>(limits.minUniformBufferOffsetAlignment, 16);
        const uint64_t ringBytes = uint64_t(std::max(config.uniformRingBytes, 256u)) * config.framesInFlight;
        ring_ = createBufferObject(ringBytes, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true, "uniform ring");
        allocations_.add(ResourceType::Buffer, kRingRecordKey,
                         {ResourceType::Buffer, "uniform ring", "rhi.internal", ring_.bytes});

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        poolInfo.queueFamilyIndex = ctx_->queueFamily;
        vkCheck(vkCreateCommandPool(ctx_->device, &poolInfo, nullptr, &immediatePool_),
                "vkCreateCommandPool");
        ctx_->name(VK_OBJECT_TYPE_COMMAND_POOL, immediatePool_, "immediate commands");
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = immediatePool_;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vkCheck(vkAllocateCommandBuffers(ctx_->device, &alloc, &immediateCmd_), "vkAllocateCommandBuffers");
        ctx_->name(VK_OBJECT_TYPE_COMMAND_BUFFER, immediateCmd_, "immediate commands");
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vkCheck(vkCreateFence(ctx_->device, &fenceInfo, nullptr, &immediateFence_), "vkCreateFence");
        ctx_->name(VK_OBJECT_TYPE_FENCE, immediateFence_, "immediate commands done");

        if (config.window) swapchain_ = std::make_unique<Swapchain>(*ctx_, *config.window, allocations_);
        list_ = std::make_unique<VulkanCommandList>(*this);
        garbage_.reserve(256);
        newTextures_.reserve(256);
    } catch (const BackendUnavailable&) {
        shutdown();
        throw;
    } catch (const Error& e) {
        shutdown();
        throw BackendUnavailable(e.what());
    }
    log::info("rhi: vulkan backend on '" + caps_.deviceName + "' (" +
              deviceTypeName(ctx_->properties.deviceType) + ", Vulkan " +
              std::to_string(VK_API_VERSION_MAJOR(ctx_->properties.apiVersion)) + "." +
              std::to_string(VK_API_VERSION_MINOR(ctx_->properties.apiVersion)) + "), driver '" +
              caps_.driverName + "'" + (config.validation ? ", validation on" : "") +
              (config.window ? ", presenting to a window" : ""));
}

VulkanDevice::~VulkanDevice() {
    shutdown();
}

void VulkanDevice::createFrames() {
    frames_.resize(config_.framesInFlight);
    for (uint32_t i = 0; i < frames_.size(); ++i) {
        FrameSlot& f = frames_[i];
        const std::string suffix = " (frame slot " + std::to_string(i) + ")";
        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        poolInfo.queueFamilyIndex = ctx_->queueFamily;
        vkCheck(vkCreateCommandPool(ctx_->device, &poolInfo, nullptr, &f.pool), "vkCreateCommandPool");
        ctx_->name(VK_OBJECT_TYPE_COMMAND_POOL, f.pool, "frame commands" + suffix);
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = f.pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vkCheck(vkAllocateCommandBuffers(ctx_->device, &alloc, &f.cmd), "vkAllocateCommandBuffers");
        ctx_->name(VK_OBJECT_TYPE_COMMAND_BUFFER, f.cmd, "frame commands" + suffix);
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT; // the first wait on each slot returns at once
        vkCheck(vkCreateFence(ctx_->device, &fenceInfo, nullptr, &f.fence), "vkCreateFence");
        ctx_->name(VK_OBJECT_TYPE_FENCE, f.fence, "frame done" + suffix);
        if (config_.window) {
            VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
            vkCheck(vkCreateSemaphore(ctx_->device, &si, nullptr, &f.acquired), "vkCreateSemaphore");
            ctx_->name(VK_OBJECT_TYPE_SEMAPHORE, f.acquired, "swapchain image acquired" + suffix);
        }
    }
}

void VulkanDevice::shutdown() {
    if (!ctx_ || !ctx_->device) {
        ctx_.reset();
        return;
    }
    const VkDevice device = ctx_->device;
    vkDeviceWaitIdle(device);
    list_.reset();
    // Resources the application did not destroy go with the device.
    buffers.forEach([&](BufferHandle, VulkanBuffer& b) { destroyBufferObject(b); });
    textures.forEach([&](TextureHandle, VulkanTexture& t) { destroyTextureObject(t); });
    samplers.forEach([&](SamplerHandle, VulkanSampler& s) { vkDestroySampler(device, s.sampler, nullptr); });
    graphicsPipelines.forEach([&](GraphicsPipelineHandle, VulkanPipeline& p) { destroyPipelineObject(p); });
    computePipelines.forEach([&](ComputePipelineHandle, VulkanPipeline& p) { destroyPipelineObject(p); });
    for (Garbage& g : garbage_)
        g.release();
    garbage_.clear();
    swapchain_.reset();
    timestamps_.destroy(device);
    for (FrameSlot& f : frames_) {
        if (f.pool) vkDestroyCommandPool(device, f.pool, nullptr);
        if (f.fence) vkDestroyFence(device, f.fence, nullptr);
        if (f.acquired) vkDestroySemaphore(device, f.acquired, nullptr);
    }
    frames_.clear();
    destroyBufferObject(ring_);
    destroyBufferObject(staging_);
    if (immediatePool_) vkDestroyCommandPool(device, immediatePool_, nullptr);
    if (immediateFence_) vkDestroyFence(device, immediateFence_, nullptr);
    immediatePool_ = VK_NULL_HANDLE;
    immediateFence_ = VK_NULL_HANDLE;
    ctx_.reset();
}

void VulkanDevice::retire(std::function<void()> release) {
    if (!inFrame_ && completed_ >= submitted_) {
        release();
        return;
    }
    // The frame being recorded, or the last one submitted, may still use the object.
    garbage_.push_back({inFrame_ ? frame_ : submitted_, std::move(release)});
}

void VulkanDevice::collectGarbage() {
    auto done = [&](const Garbage& g) { return g.frame <= completed_; };
    for (Garbage& g : garbage_)
        if (done(g)) g.release();
    garbage_.erase(std::remove_if(garbage_.begin(), garbage_.end(), done), garbage_.end());
}

void VulkanDevice::flushNewTextures(VkCommandBuffer cmd) {
    BarrierBatch barriers(cmd);
    for (TextureHandle h : newTextures_)
        if (textures.contains(h)) barriers.transitionHome(textures.get(h));
    newTextures_.clear();
}

uint64_t VulkanDevice::pushToRing(const void* data, uint32_t size) {
    const uint64_t region = std::max(config_.uniformRingBytes, 256u);
    const uint64_t offset = (ringCursor_ + ringAlignment_ - 1) / ringAlignment_ * ringAlignment_;
    if (offset + size > region)
        throw Error("pushUniforms: more than " + std::to_string(region) +
                    " bytes in one frame (raise DeviceConfig::uniformRingBytes)");
    ringCursor_ = offset + size;
    const uint64_t at = region * frameSlot() + offset;
    std::memcpy(static_cast<std::byte*>(ring_.mapped) + at, data, size);
    return at;
}

CommandList& VulkanDevice::beginFrame() {
    if (inFrame_) throw Error("beginFrame() called twice without endFrame()");
    FrameSlot& f = frames_[(frame_ + 1) % frames_.size()];
    // Wait for the frame that last used this slot (framesInFlight frames ago).
    vkCheck(vkWaitForFences(ctx_->device, 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    completed_ = std::max(completed_, f.frame);
    collectGarbage();

    ++frame_;
    vkCheck(vkResetCommandPool(ctx_->device, f.pool, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(f.cmd, &begin), "vkBeginCommandBuffer");
    inFrame_ = true;
    list_->resetCounts();
    // Nothing to order this frame after: every command buffer submitted before it ends with a full
    // barrier (the last frame's end, and each immediate transfer's).
    timestamps_.beginFrame(f.cmd, frame_);
    ringCursor_ = 0;
    flushNewTextures(f.cmd);
    list_->begin(f.cmd);
    return *list_;
}

void VulkanDevice::recordPresent(VkCommandBuffer cmd, VulkanTexture& source, uint32_t imageIndex) {
    const VkImage target = swapchain_->image(imageIndex);
    const VkExtent2D extent = swapchain_->extent();
    transition(cmd, source, 0, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);

    VkImageMemoryBarrier2 toBlit{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    // ALL_COMMANDS matches the stage the acquire semaphore is waited at, chaining the two.
    toBlit.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    toBlit.srcAccessMask = 0;
    toBlit.dstStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    toBlit.dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toBlit.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED; // the whole image is overwritten
    toBlit.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toBlit.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toBlit.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    toBlit.image = target;
    toBlit.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &toBlit;
    cmdPipelineBarrier2(cmd, dep);

    // Straight blit: memory row 0 of the texture becomes the top row of the window.
    VkImageBlit region{};
    region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffsets[1] = {int32_t(source.width(0)), int32_t(source.height(0)), 1};
    region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.dstOffsets[1] = {int32_t(extent.width), int32_t(extent.height), 1};
    vkCmdBlitImage(cmd, source.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region, VK_FILTER_LINEAR);

    VkImageMemoryBarrier2 toPresent = toBlit;
    toPresent.srcStageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
    toPresent.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    // The semaphore signal (at ALL_COMMANDS) orders the present after this transition.
    toPresent.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    toPresent.dstAccessMask = 0;
    toPresent.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    toPresent.newLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    dep.pImageMemoryBarriers = &toPresent;
    cmdPipelineBarrier2(cmd, dep);

    transitionHome(cmd, source);
}

void VulkanDevice::endFrame(TextureHandle present) {
    if (!inFrame_) throw Error("endFrame() without beginFrame()");
    list_->finish();
    FrameSlot& f = frames_[frameSlot()];

    bool presenting = false;
    uint32_t imageIndex = 0;
    if (present) {
        VulkanTexture& source = textures.get(present);
        if (isIntegerFormat(source.desc.format) || isDepthFormat(source.desc.format))
            throw Error("endFrame: texture '" + source.desc.debugName + "' (" +
                        std::string(formatName(source.desc.format)) + ") cannot be presented");
        if (swapchain_) {
            presenting = swapchain_->acquire(f.acquired, imageIndex);
            if (presenting) recordPresent(f.cmd, source, imageIndex);
        }
    }
    lastFrame_ = list_->counts();
    vkCheck(vkEndCommandBuffer(f.cmd), "vkEndCommandBuffer");

    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = f.cmd;
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    if (presenting) {
        wait.semaphore = f.acquired;
        wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        signal.semaphore = swapchain_->renderFinished(imageIndex);
        signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        submit.waitSemaphoreInfoCount = 1;
        submit.pWaitSemaphoreInfos = &wait;
        submit.signalSemaphoreInfoCount = 1;
        submit.pSignalSemaphoreInfos = &signal;
    }
    vkCheck(vkResetFences(ctx_->device, 1, &f.fence), "vkResetFences");
    inFrame_ = false;
    vkCheck(vkQueueSubmit2(ctx_->queue, 1, &submit, f.fence), "vkQueueSubmit2");
    f.frame = frame_;
    submitted_ = frame_;
    if (presenting) swapchain_->present(imageIndex);
}

bool VulkanDevice::readTimestamps(uint64_t frame, std::span<uint64_t> nanoseconds) {
    return timestamps_.read(ctx_->device, frame, submitted_, nanoseconds);
}

void VulkanDevice::waitIdle() {
    vkCheck(vkDeviceWaitIdle(ctx_->device), "vkDeviceWaitIdle");
    markAllComplete();
    collectGarbage();
}

} // namespace lpv::rhi::vk

namespace lpv::rhi {

std::unique_ptr<Device> createVulkanDevice(const DeviceConfig& config) {
    return std::make_unique<vk::VulkanDevice>(config);
}

} // namespace lpv::rhi
