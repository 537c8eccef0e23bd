// Recording of one frame into its VkCommandBuffer: dynamic rendering for passes, push descriptors
// for every binding the bound pipeline declares (pushed at each draw and dispatch), and the RHI's
// automatic barriers around passes, dispatches and transfers.
#pragma once

#include "VkBarriers.h"
#include "VkResources.h"

#include "rhi/CommandList.h"

#include <vulkan/vulkan.h>

#include <array>
#include <span>

namespace lpv::rhi::vk {

class VulkanDevice;

class VulkanCommandList final : public CommandList {
public:
    explicit VulkanCommandList(VulkanDevice& device) : device_(device) {}

    // Starts recording a frame into `cmd`: forgets every binding of the previous frame.
    void begin(VkCommandBuffer cmd);
    // Checks the frame can be submitted and closes markers left open.
    void finish();
    // Starts this frame's counts (before the device's own barriers at the frame's start).
    void resetCounts();
    CommandCounts counts() const override;

    void beginRenderPass(const RenderPassDesc& desc) override;
    void endRenderPass() override;
    void setViewport(const Viewport& vp) override;
    void setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) override;
    void bindPipeline(GraphicsPipelineHandle pipeline) override;
    void bindPipeline(ComputePipelineHandle pipeline) override;
    void bindVertexBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset) override;
    void bindIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset) override;
    void bindUniformBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size) override;
    void bindStorageBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size) override;
    void bindTexture(uint32_t binding, TextureHandle texture, SamplerHandle sampler) override;
    void bindStorageImage(uint32_t binding, TextureHandle texture, uint32_t mipLevel) override;
    void pushUniforms(uint32_t binding, const void* data, uint32_t size) override;
    void draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
              uint32_t firstInstance) override;
    void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t vertexOffset,
                     uint32_t firstInstance) override;
    void drawIndexedIndirect(BufferHandle commands, uint64_t offset, uint32_t drawCount) override;
    void dispatch(uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) override;
    void clearTexture(TextureHandle texture, const std::array<float, 4>& value) override;
    void updateBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint32_t size) override;
    void copyTextures(std::span<const TextureCopy> copies) override;
    void writeTimestamp(uint32_t slot) override;
    void beginMarker(const char* name) override;
    void endMarker() override;

private:
    enum class BoundKind : uint8_t { None, UniformBuffer, StorageBuffer, Texture, StorageImage };
    struct Bound {
        BoundKind kind = BoundKind::None;
        uint64_t resource = 0; // the VkImage or VkBuffer, for hazard tracking
        VkDescriptorBufferInfo buffer{};
        VkDescriptorImageInfo image{};
    };
    struct PassTarget {
        TextureHandle texture;
        uint32_t mip = 0;
        VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED; // drawn in
        static constexpr uint32_t kAllMips = ~0u;
    };

    void requireFrame(const char* what) const;
    void requirePass(bool inside, const char* what) const;
    Bound& slot(uint32_t binding, const char* what);
    void bindBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size, bool storage);
    void clearBindings();
    // Pushes the descriptors the bound pipeline of `bindPoint` declares; throws if one is missing.
    void pushBindings(const VulkanPipeline& pipeline);
    // Dispatches and transfers leave their barrier owed: recorded before the next command that reads
    // or writes what they wrote (or writes what they read), merged into that command's own barrier
    // when it has one, and before anything else (passes, the frame's end).
    bool owedHazard(uint64_t resource, bool writes) const;
    bool dispatchHazard(const VulkanPipeline& p) const;
    // Adds `resource` to what the owed barrier covers (0: no resource, only the ordering).
    void owe(uint64_t resource, bool writes);
    void noteDispatchAccesses(const VulkanPipeline& p);
    // Records the owed barrier now (into `batch` when given). Returns whether one was owed.
    bool payOwed(BarrierBatch* batch = nullptr);
    // A render pass owes its barrier too (its targets back home, its writes visible), to the next
    // command, which pays it in its own: into `batch`, leaving in place the targets in `keep` that
    // the next command moves itself (mip kAllMips: every mip). Returns whether one was owed.
    bool payPass(BarrierBatch& batch, std::span<const PassTarget> keep = {});
    // Both owed barriers, into one call, if either is owed.
    void payAll();
    // Passes begin at their first draw: with unified layouts, where they have no moves of their own.
    bool deferredBegin() const;
    // vkCmdBeginRendering for the current pass; with a deferred begin, behind a barrier where its
    // targets or `firstDraw`'s bindings (null: none) meet a hazard.
    void startRendering(const VulkanPipeline* firstDraw);
    // Before each draw: begins a deferred pass, or stops it for a barrier a later draw needs.
    void beforeDraw(const VulkanPipeline& p);
    bool drawHazard(const VulkanPipeline& p) const;
    void noteDrawAccesses(const VulkanPipeline& p);
    void beginLabel(const char* name);
    void endLabel();

    VulkanDevice& device_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    std::array<Bound, kMaxBindings> bound_{};
    GraphicsPipelineHandle graphics_;
    ComputePipelineHandle compute_;
    std::array<PassTarget, RenderPassDesc::kMaxColorTargets + 1> passTargets_{};
    uint32_t passTargetCount_ = 0;
    bool passOwed_ = false; // the last pass's barrier: its targets are still in passTargets_
    VkExtent2D passExtent_{0, 0};
    bool inPass_ = false;
    // The current pass, kept so that it can begin later (deferredBegin) or begin again after a
    // barrier.
    bool rendering_ = false; // vkCmdBeginRendering recorded for the current pass
    VkRenderingInfo passInfo_{};
    std::array<VkRenderingAttachmentInfo, RenderPassDesc::kMaxColorTargets> passColors_{};
    VkRenderingAttachmentInfo passDepth_{};
    // Bound for draws, for their hazards (0: none).
    std::array<uint64_t, 8> vertexBuffers_{};
    uint64_t indexBuffer_ = 0;
    uint64_t indexOffset_ = 0; // drawIndexedIndirect's rule: 0, as GL's multi-draw needs
    uint32_t markerDepth_ = 0;
    static constexpr uint32_t kMaxTracked = 64;
    std::array<uint64_t, kMaxTracked> written_{}, read_{}; // since the owed barrier's dispatches
    uint32_t writtenCount_ = 0, readCount_ = 0;
    // More than kMaxTracked: every resource counts as written (read) until the barrier is paid.
    bool writtenOverflow_ = false, readOverflow_ = false;
    bool owed_ = false;
    uint64_t barrierBase_ = 0; // pipelineBarrierCalls() when the frame began
};

} // namespace lpv::rhi::vk
