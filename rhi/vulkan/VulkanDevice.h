// The Vulkan 1.3 device: resources behind generation-checked handles, frames in flight with one
// command buffer each, immediate transfers for load time, and the per-frame uniform ring.
#pragma once

#include "VkCommandList.h"
#include "VkContext.h"
#include "VkResources.h"
#include "VkSwapchain.h"
#include "VkTimestamps.h"

#include "../src/HandlePool.h"

#include "rhi/Device.h"

#include <functional>
#include <memory>
#include <vector>

namespace lpv::rhi::vk {

class VulkanDevice final : public Device {
public:
    explicit VulkanDevice(const DeviceConfig& config);
    ~VulkanDevice() override;

    BackendKind backend() const override { return BackendKind::Vulkan; }
    const Caps& caps() const override { return caps_; }

    BufferHandle createBuffer(const BufferDesc& desc, const void* initialData) override;
    TextureHandle createTexture(const TextureDesc& desc) override;
    SamplerHandle createSampler(const SamplerDesc& desc) override;
    GraphicsPipelineHandle createPipeline(const GraphicsPipelineDesc& desc) override;
    ComputePipelineHandle createPipeline(const ComputePipelineDesc& desc) override;

    void destroy(BufferHandle h) override;
    void destroy(TextureHandle h) override;
    void destroy(SamplerHandle h) override;
    void destroy(GraphicsPipelineHandle h) override;
    void destroy(ComputePipelineHandle h) override;

    const BufferDesc& desc(BufferHandle h) const override { return buffers.get(h).desc; }
    const TextureDesc& desc(TextureHandle h) const override { return textures.get(h).desc; }

    void uploadBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) override;
    void uploadTexture(TextureHandle h, uint32_t mipLevel, const void* data, uint64_t size) override;
    void readBuffer(BufferHandle h, uint64_t offset, void* out, uint64_t size) override;
    void readTexture(TextureHandle h, uint32_t mipLevel, void* out, uint64_t size) override;
    void* mapped(BufferHandle h) override;

    CommandList& beginFrame() override;
    void endFrame(TextureHandle present) override;
    uint64_t frameIndex() const override { return frame_; }
    CommandCounts frameCounters() const override { return lastFrame_; }
    bool conservativeBarriers() const { return conservativeBarriers_; }
    // Every texture lives in VK_IMAGE_LAYOUT_GENERAL (DeviceConfig::unifiedImageLayouts): no
    // layout moves, so render passes are ordered by their hazards alone.
    bool unifiedImageLayouts() const { return unifiedImageLayouts_; }
    bool readTimestamps(uint64_t frame, std::span<uint64_t> nanoseconds) override;
    void waitIdle() override;

    const AllocationRecord& allocations() const override { return allocations_; }

    // Used by the command list.
    const VulkanContext& context() const { return *ctx_; }
    bool inFrame() const { return inFrame_; }
    VkCommandBuffer frameCommands() const { return frames_[frameSlot()].cmd; }
    // Copies `size` bytes into this frame's region of the uniform ring; returns the buffer offset.
    uint64_t pushToRing(const void* data, uint32_t size);
    VkBuffer ringBuffer() const { return ring_.buffer; }
    // Moves textures created since the last call from UNDEFINED to their home layout.
    void flushNewTextures(VkCommandBuffer cmd);
    TimestampRing& timestamps() { return timestamps_; }

    HandlePool<BufferTag, VulkanBuffer> buffers;
    HandlePool<TextureTag, VulkanTexture> textures;
    HandlePool<SamplerTag, VulkanSampler> samplers;
    HandlePool<GraphicsPipelineTag, VulkanPipeline> graphicsPipelines;
    HandlePool<ComputePipelineTag, VulkanPipeline> computePipelines;

private:
    struct FrameSlot {
        VkCommandPool pool = VK_NULL_HANDLE;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        VkSemaphore acquired = VK_NULL_HANDLE; // swapchain image ready (windowed only)
        uint64_t frame = 0;                    // frame last submitted from this slot
    };
    // A Vulkan object release waiting until the GPU is done with the frame that may use it.
    struct Garbage {
        uint64_t frame = 0;
        std::function<void()> release;
    };

    uint32_t frameSlot() const { return uint32_t(frame_ % frames_.size()); }
    void createFrames();
    void shutdown();

    VulkanBuffer createBufferObject(uint64_t size, VkBufferUsageFlags usage, bool hostVisible,
                                    const std::string& name, bool hostReads = false);
    void destroyBufferObject(VulkanBuffer& b);
    void destroyTextureObject(VulkanTexture& t);
    void destroyPipelineObject(VulkanPipeline& p);
    // Releases now when no submitted or recording frame can use the object, else when its frame is done.
    void retire(std::function<void()> release);
    void collectGarbage();
    void markAllComplete() { completed_ = submitted_; }

    // Immediate transfers: a separate command buffer, submitted and waited for at once.
    VkCommandBuffer beginImmediate(const char* what);
    void submitImmediate();
    void ensureStaging(uint64_t size);
    void copyIntoBuffer(VulkanBuffer& b, uint64_t offset, const void* data, uint64_t size);
    // Checks `size` against the tightly packed size of `mip` (all layers/slices) of `t`.
    void checkTextureRange(const VulkanTexture& t, uint32_t mip, uint64_t size, const char* what) const;
    void checkImmediate(const char* what) const;

    void recordPresent(VkCommandBuffer cmd, VulkanTexture& source, uint32_t imageIndex);

    DeviceConfig config_;
    bool conservativeBarriers_ = false;
    bool unifiedImageLayouts_ = false;
    Caps caps_;
    AllocationRecord allocations_;
    std::unique_ptr<VulkanContext> ctx_;
    std::unique_ptr<Swapchain> swapchain_;
    std::vector<FrameSlot> frames_;
    TimestampRing timestamps_;

    VulkanBuffer ring_; // framesInFlight regions of uniformRingBytes
    uint64_t ringCursor_ = 0;
    uint64_t ringAlignment_ = 256;

    VulkanBuffer staging_; // grows on demand; shared by uploads and readbacks
    VkCommandPool immediatePool_ = VK_NULL_HANDLE;
    VkCommandBuffer immediateCmd_ = VK_NULL_HANDLE;
    VkFence immediateFence_ = VK_NULL_HANDLE;

    std::vector<Garbage> garbage_;
    std::vector<TextureHandle> newTextures_;

    std::unique_ptr<VulkanCommandList> list_;
    CommandCounts lastFrame_;
    uint64_t frame_ = 0;
    uint64_t submitted_ = 0; // last frame handed to the queue
    uint64_t completed_ = 0; // last frame known finished on the GPU
    bool inFrame_ = false;
};

} // namespace lpv::rhi::vk
