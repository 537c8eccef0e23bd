// The OpenGL 4.5 backend. Commands execute on the context as they are recorded: with one context
// and one command list per frame, recording order is execution order, which is what a replay
// would give. Barriers: glMemoryBarrier(ALL) after every dispatch and render pass.
//
// Timestamps: GL_TIME_ELAPSED and GL_TIMESTAMP read 0 or garbage on llvmpipe/softpipe
// (../shared/docs/lpv-notes.md), so there the backend uses TimestampSource::CpuFinished:
// writeTimestamp() calls glFinish() and reads the CPU clock. Elsewhere GL_TIMESTAMP queries are
// used, one set per frame slot, read with GL_QUERY_RESULT_AVAILABLE and never waited for.
#pragma once

#include "GlFunctions.h"

#include "../src/HandlePool.h"
#include "rhi/Backend.h"
#include "rhi/Device.h"

#include <array>
#include <map>
#include <memory>
#include <vector>

namespace lpv::rhi::gl {

struct GlBuffer {
    BufferDesc desc;
    GLuint id = 0;
    void* mapped = nullptr;
};

struct GlTexture {
    TextureDesc desc;
    GLuint id = 0;
    GLenum target = 0;
};

struct GlSampler {
    GLuint id = 0;
};

struct GlGraphicsPipeline {
    GraphicsPipelineDesc desc;
    GLuint program = 0;
    GLuint vao = 0;
    GLint baseInstanceLocation = -1; // SPIRV-Cross's emulation of gl_InstanceIndex's base
};

struct GlComputePipeline {
    GLuint program = 0;
};

class GlDevice;

class GlCommandList final : public CommandList {
public:
    explicit GlCommandList(GlDevice& device) : device_(device) {}
    void reset();

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
    void dispatch(uint32_t x, uint32_t y, uint32_t z) override;
    void clearTexture(TextureHandle texture, const std::array<float, 4>& value) override;
    void updateBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint32_t size) override;
    void copyTexture(TextureHandle src, TextureHandle dst) override;
    void writeTimestamp(uint32_t slot) override;
    void beginMarker(const char* name) override;
    void endMarker() override;

private:
    void requireOutsidePass(const char* what) const;
    void prepareDraw();

    GlDevice& device_;
    bool inPass_ = false;
    uint32_t passWidth_ = 0, passHeight_ = 0;
    GlGraphicsPipeline* graphics_ = nullptr;
    GraphicsPipelineHandle graphicsHandle_;
    struct VertexBinding {
        GLuint buffer = 0;
        uint64_t offset = 0;
    };
    std::array<VertexBinding, 8> vertexBuffers_{};
    GLuint indexBuffer_ = 0;
    uint64_t indexOffset_ = 0;
    IndexType indexType_ = IndexType::Uint32;
};

class GlDevice final : public Device {
public:
    GlDevice(const DeviceConfig& config, std::unique_ptr<platforms::GlContext> context);
    ~GlDevice() override;

    BackendKind backend() const override { return BackendKind::OpenGL; }
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
    bool readTimestamps(uint64_t frame, std::span<uint64_t> nanoseconds) override;
    void waitIdle() override;
    const AllocationRecord& allocations() const override { return allocations_; }

    // For the command list.
    const Functions& gl() const { return gl_; }
    GLuint framebufferFor(const RenderPassDesc& desc);
    uint64_t allocateUniforms(const void* data, uint32_t size); // returns the ring offset
    GLuint uniformRing() const { return uniformRing_; }
    void recordTimestamp(uint32_t slot);
    bool inFrame() const { return inFrame_; }
    void label(GLenum type, GLuint id, const std::string& name) const;

    HandlePool<BufferTag, GlBuffer> buffers;
    HandlePool<TextureTag, GlTexture> textures;
    HandlePool<SamplerTag, GlSampler> samplers;
    HandlePool<GraphicsPipelineTag, GlGraphicsPipeline> graphicsPipelines;
    HandlePool<ComputePipelineTag, GlComputePipeline> computePipelines;

private:
    void requireOutsideFrame(const char* what) const;
    static uint64_t mipBytes(const TextureDesc& d, uint32_t mip);
    GLuint linkProgram(std::initializer_list<const ShaderBinary*> stages, const std::string& name);

    DeviceConfig config_;
    std::unique_ptr<platforms::GlContext> context_;
    Functions gl_;
    Caps caps_;
    AllocationRecord allocations_;
    GlCommandList list_;
    uint64_t frame_ = 0;
    bool inFrame_ = false;

    GLuint uniformRing_ = 0;
    uint64_t uniformHead_ = 0;
    uint64_t uniformAlignment_ = 256;

    // Framebuffers by attachment set, made on first use. Keys hold texture names; destroying a
    // texture drops the framebuffers that use it.
    std::map<std::vector<uint64_t>, GLuint> framebuffers_;
    std::vector<uint64_t> fboKey_;
    GLuint presentFbo_ = 0;

    struct FrameSlot {
        uint64_t frame = 0;
        bool complete = false;
        GLsync fence = nullptr;
        std::vector<uint64_t> cpuTimes; // CpuFinished
        std::vector<GLuint> queries;    // GpuQueries
        std::vector<bool> written;
    };
    std::vector<FrameSlot> slots_;
    FrameSlot& slot(uint64_t frame) { return slots_[frame % slots_.size()]; }
};

} // namespace lpv::rhi::gl
