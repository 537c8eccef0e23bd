// The GL backend's command list. Commands execute on the context as they are recorded: with one
// context and one list per frame, recording order is execution order, which is exactly what a
// later replay would produce, without a second copy of every argument. Barriers follow the RHI
// rule: a command pays one glMemoryBarrier, with the bits its own accesses need, only where it
// touches what earlier shaders stored to (or stores to what they read) since a barrier covered it
// (GlHazards); DeviceConfig::conservativeBarriers restores glMemoryBarrier(GL_ALL_BARRIER_BITS)
// after every dispatch, render pass and transfer.
#pragma once

#include "GlFunctions.h"
#include "GlHazards.h"
#include "GlResources.h"

#include "rhi/CommandList.h"

#include <array>

namespace lpv::rhi::gl {

class GlDevice;

class GlCommandList final : public CommandList {
public:
    explicit GlCommandList(GlDevice& device) : device_(device) {}
    void begin();
    // Closes what the frame left open (markers) and makes every shader store visible to the host
    // and the next frame: returns whether that took a barrier. Throws inside a render pass.
    bool finish();
    // The device's own glMemoryBarrier at endFrame(), counted with the frame's.
    void countBarrier() { ++counts_.barriers; }

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

    // Bindings are numbered like Vulkan descriptors in set 0, below rhi::kMaxBindings.
    static constexpr uint32_t kMaxVertexBuffers = 8;

private:
    void requireFrame(const char* what) const;
    void requirePass(bool inside, const char* what) const;
    void checkBinding(uint32_t binding, const char* what) const;
    void bindBuffer(GLenum target, uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size);
    GlGraphicsPipeline& prepareDraw(const char* what, bool indexed);
    void useProgram(GLuint program);
    // The bound pipeline's depth and stencil write masks, after a clear that needed them open.
    void restoreWriteMasks();
    // glMemoryBarrier(bits), counted, when bits is not 0.
    void barrier(GLbitfield bits);
    // Before and after a draw or dispatch with these bindings (and, for a draw, its vertex and
    // index buffers): the barrier it needs, then what its shaders read and may have stored.
    GLbitfield shaderHazards(const std::vector<ShaderBinding>& bindings) const;
    void noteShaderAccesses(const std::vector<ShaderBinding>& bindings);
    // After a dispatch, render pass or transfer: the conservative rule's barrier, if it is on.
    void conservativeBarrier();

    GlDevice& device_;
    bool inPass_ = false;
    uint32_t markerDepth_ = 0;
    // Handles, not pointers: a pipeline created mid-frame may move the pool's storage.
    GraphicsPipelineHandle graphics_;
    ComputePipelineHandle compute_;
    GLuint activeProgram_ = 0; // graphics and compute share glUseProgram; Vulkan has two bind points
    struct VertexBinding {
        GLuint buffer = 0;
        uint64_t offset = 0;
    };
    std::array<VertexBinding, kMaxVertexBuffers> vertexBuffers_{};
    GLuint indexBuffer_ = 0;
    uint64_t indexOffset_ = 0;
    IndexType indexType_ = IndexType::Uint32;
    // What each binding holds, as GlHazards keys (0: nothing to track, e.g. pushed uniforms).
    std::array<uint64_t, kMaxBindings> bound_{};
    GlHazards hazards_;
};

} // namespace lpv::rhi::gl
