// The OpenGL 4.5 core backend's device: owns the context, the loaded entry points, the handle
// pools and the per-frame machinery (fences, uniform ring, timestamps). Conventions are Vulkan's:
// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE) gives depth 0..1, and with no y-flip anywhere NDC
// y = -1 lands in memory row 0 on both APIs. Only presentation flips (row 0 shows at the top).
#pragma once

#include "GlCommandList.h"
#include "GlDebugOutput.h"
#include "GlFramebuffers.h"
#include "GlFunctions.h"
#include "GlResources.h"
#include "GlTimestamps.h"
#include "GlUniformRing.h"

#include "../src/HandlePool.h"
#include "rhi/Backend.h"
#include "rhi/Device.h"

#include <memory>
#include <vector>

namespace lpv::rhi::gl {

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
    CommandCounts frameCounters() const override { return lastFrame_; }
    bool readTimestamps(uint64_t frame, std::span<uint64_t> nanoseconds) override;
    void waitIdle() override;
    const AllocationRecord& allocations() const override { return allocations_; }

    // For the command list.
    const Functions& gl() const { return gl_; }
    bool inFrame() const { return inFrame_; }
    bool conservativeBarriers() const { return conservativeBarriers_; }
    GlFramebufferCache& framebuffers() { return framebuffers_; }
    GlUniformRing& uniformRing() { return uniformRing_; }
    GlTimestamps& timestamps() { return timestamps_; }

    HandlePool<BufferTag, GlBuffer> buffers;
    HandlePool<TextureTag, GlTexture> textures;
    HandlePool<SamplerTag, GlSampler> samplers;
    HandlePool<GraphicsPipelineTag, GlGraphicsPipeline> graphicsPipelines;
    HandlePool<ComputePipelineTag, GlComputePipeline> computePipelines;

private:
    void requireOutsideFrame(const char* what) const;
    const GlTexture& transferTexture(TextureHandle h, uint32_t mip, uint64_t size, const char* what) const;
    GLuint linkProgram(std::initializer_list<const ShaderBinary*> stages, const std::string& name);
    void checkStorageImageUnits(GLuint program, const std::string& name) const;
    void present(const GlTexture& source);
    void releaseAll();

    // Handle bits the allocation record files the backend's own buffers under (never a real handle:
    // generation 0 is not handed out).
    static constexpr uint32_t kUniformRingRecord = 0x0000fffeu;

    DeviceConfig config_;
    std::unique_ptr<platforms::GlContext> context_;
    Functions gl_;
    ObjectLabeler label_;
    Caps caps_;
    AllocationRecord allocations_;
    GlCommandList list_;
    CommandCounts lastFrame_;
    GlFramebufferCache framebuffers_;
    GlUniformRing uniformRing_;
    GlTimestamps timestamps_;
    std::vector<GLsync> fences_; // one per frame in flight: frame F waits for F - framesInFlight
    GLuint presentFramebuffer_ = 0;
    uint64_t frame_ = 0;
    bool inFrame_ = false;
    bool conservativeBarriers_ = false; // DeviceConfig's, or LPV_CONSERVATIVE_BARRIERS=1
};

} // namespace lpv::rhi::gl
