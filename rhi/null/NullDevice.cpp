// The null backend: no GPU, but the same handle pools, allocation record and argument checks as
// the real backends. Front-end logic (handle lifetime, memory accounting, frame bookkeeping,
// profiler timing rings) is tested against it without a device. Buffers keep their bytes so uploads
// read back; textures read back as zeros. Timestamps are simulated: every recorded command costs
// 1 us of "GPU time", and a frame's results become readable once the frame is complete, which is
// when frame + framesInFlight begins (the real backends' fence rule) or after waitIdle().
#include "../src/BackendFactory.h"
#include "../src/DescValidation.h"
#include "../src/HandlePool.h"

#include "rhi/Error.h"

#include <algorithm>
#include <cstring>
#include <vector>

namespace lpv::rhi {
namespace {

struct NullBuffer {
    BufferDesc desc;
    std::vector<std::byte> bytes;
};
struct NullTexture {
    TextureDesc desc;
};
struct NullSampler {
    SamplerDesc desc;
};
struct NullGraphicsPipeline {
    std::string name;
};
struct NullComputePipeline {
    std::string name;
};

class NullDevice;

class NullCommandList final : public CommandList {
public:
    explicit NullCommandList(NullDevice& device) : device_(device) {}
    void beginRenderPass(const RenderPassDesc& desc) override;
    void endRenderPass() override {
        inPass_ = false;
        ++counts_.barriers;
    }
    void setViewport(const Viewport&) override {}
    void setScissor(int32_t, int32_t, uint32_t, uint32_t) override {}
    void bindPipeline(GraphicsPipelineHandle p) override;
    void bindPipeline(ComputePipelineHandle p) override;
    void bindVertexBuffer(uint32_t, BufferHandle b, uint64_t) override;
    void bindIndexBuffer(BufferHandle b, IndexType, uint64_t) override;
    void bindUniformBuffer(uint32_t, BufferHandle b, uint64_t, uint64_t) override;
    void bindStorageBuffer(uint32_t, BufferHandle b, uint64_t, uint64_t) override;
    void bindTexture(uint32_t, TextureHandle t, SamplerHandle s) override;
    void bindStorageImage(uint32_t binding, TextureHandle t, uint32_t) override;
    void pushUniforms(uint32_t, const void*, uint32_t) override {}
    void draw(uint32_t, uint32_t, uint32_t, uint32_t) override {
        requirePass(true, "draw");
        ++counts_.draws;
        countStage(counts_.barriers);
    }
    void drawIndexed(uint32_t, uint32_t, uint32_t, int32_t, uint32_t) override {
        requirePass(true, "drawIndexed");
        ++counts_.drawsIndexed;
        countStage(counts_.barriers);
    }
    void drawIndexedIndirect(BufferHandle, uint64_t, uint32_t) override {
        requirePass(true, "drawIndexedIndirect");
        ++counts_.drawsIndexed;
        countStage(counts_.barriers);
    }
    // Barriers: one after each dispatch, pass, clear and copy, two around a buffer update (the
    // Vulkan backend's conservative rule, DeviceConfig::conservativeBarriers).
    void dispatch(uint32_t, uint32_t, uint32_t) override {
        requirePass(false, "dispatch");
        ++counts_.dispatches;
        countStage(counts_.barriers);
        ++counts_.barriers;
    }
    void clearTexture(TextureHandle t, const std::array<float, 4>&) override;
    void updateBuffer(BufferHandle b, uint64_t offset, const void* data, uint32_t size) override;
    void copyTextures(std::span<const TextureCopy> copies) override;
    void writeTimestamp(uint32_t slot) override;
    void beginMarker(const char*) override {}
    void endMarker() override {}

    using CommandList::resetCounts;

private:
    // Checks pass state and advances the simulated GPU clock: every command "costs" 1 us.
    void requirePass(bool inside, const char* what) const;
    NullDevice& device_;
    bool inPass_ = false;
};

class NullDevice final : public Device {
public:
    explicit NullDevice(const DeviceConfig& config) : list_(*this) {
        caps_.deviceName = "null device";
        caps_.driverName = "none";
        caps_.timestampSource = TimestampSource::Simulated;
        caps_.drawsPixels = false;
        caps_.maxTimestampsPerFrame = config.maxTimestampsPerFrame;
        timestamps_.resize(config.framesInFlight + 1);
        for (FrameTimestamps& t : timestamps_)
            t.ns.assign(config.maxTimestampsPerFrame, 0);
        caps_.framesInFlight = config.framesInFlight;
        caps_.max3DTextureSize = 2048;
        caps_.max2DTextureSize = 16384;
        caps_.maxColorTargets = RenderPassDesc::kMaxColorTargets;
        caps_.vertexShaderLayer = config.vertexShaderLayer;
        caps_.maskedBranches = config.maskedBranches.value_or(false);
        caps_.shaderStencilExport = true; // it runs no shader, so any may export
        caps_.multiDrawIndirect = config.multiDrawIndirect.value_or(true);
        caps_.fragmentStores = true;
        caps_.storageImageBindings = configuredStorageImageBindings(32, config.storageImageBindings);
        caps_.fragmentTextureBindings =
            std::min(kMaxBindings, config.fragmentTextureBindings.value_or(kMaxBindings));
        caps_.computeTextureBindings = kMaxBindings;
    }

    BackendKind backend() const override { return BackendKind::Null; }
    const Caps& caps() const override { return caps_; }

    BufferHandle createBuffer(const BufferDesc& desc, const void* initialData) override {
        if (desc.size == 0) throw Error("buffer '" + desc.debugName + "': size is 0");
        NullBuffer b{desc, std::vector<std::byte>(desc.size)};
        if (initialData) std::memcpy(b.bytes.data(), initialData, desc.size);
        const BufferHandle h = buffers.insert(std::move(b));
        allocations_.add(ResourceType::Buffer, h.bits,
                         {ResourceType::Buffer, desc.debugName, desc.category, desc.size});
        return h;
    }
    TextureHandle createTexture(const TextureDesc& desc) override {
        validateTextureDesc(desc, caps_);
        const TextureHandle h = textures.insert({desc});
        allocations_.add(ResourceType::Texture, h.bits,
                         {ResourceType::Texture, desc.debugName, desc.category, textureBytes(desc)});
        return h;
    }
    SamplerHandle createSampler(const SamplerDesc& desc) override { return samplers.insert({desc}); }
    GraphicsPipelineHandle createPipeline(const GraphicsPipelineDesc& desc) override {
        if (!desc.vertex) throw Error("graphics pipeline '" + desc.debugName + "': no vertex shader");
        validateStencilState(desc);
        return graphicsPipelines.insert({desc.debugName});
    }
    ComputePipelineHandle createPipeline(const ComputePipelineDesc& desc) override {
        if (!desc.compute) throw Error("compute pipeline '" + desc.debugName + "': no compute shader");
        return computePipelines.insert({desc.debugName});
    }

    void destroy(BufferHandle h) override {
        buffers.remove(h);
        allocations_.remove(ResourceType::Buffer, h.bits);
    }
    void destroy(TextureHandle h) override {
        textures.remove(h);
        allocations_.remove(ResourceType::Texture, h.bits);
    }
    void destroy(SamplerHandle h) override { samplers.remove(h); }
    void destroy(GraphicsPipelineHandle h) override { graphicsPipelines.remove(h); }
    void destroy(ComputePipelineHandle h) override { computePipelines.remove(h); }

    const BufferDesc& desc(BufferHandle h) const override { return buffers.get(h).desc; }
    const TextureDesc& desc(TextureHandle h) const override { return textures.get(h).desc; }

    void uploadBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) override {
        NullBuffer& b = buffers.get(h);
        checkRange(b, offset, size);
        std::memcpy(b.bytes.data() + offset, data, size);
    }
    void uploadTexture(TextureHandle h, uint32_t, const void*, uint64_t) override { textures.get(h); }
    void readBuffer(BufferHandle h, uint64_t offset, void* out, uint64_t size) override {
        NullBuffer& b = buffers.get(h);
        checkRange(b, offset, size);
        std::memcpy(out, b.bytes.data() + offset, size);
    }
    void readTexture(TextureHandle h, uint32_t, void* out, uint64_t size) override {
        textures.get(h);
        std::memset(out, 0, size);
    }
    void* mapped(BufferHandle h) override {
        NullBuffer& b = buffers.get(h);
        if (b.desc.access == MemoryAccess::GpuOnly)
            throw Error("buffer '" + b.desc.debugName + "' is not MemoryAccess::HostWrite or HostRead");
        return b.bytes.data();
    }

    CommandList& beginFrame() override {
        if (inFrame_) throw Error("beginFrame() called twice without endFrame()");
        inFrame_ = true;
        ++frame_;
        list_.resetCounts();
        // Beginning frame F waits for frame F - framesInFlight, as a real device's fence does.
        if (frame_ > caps_.framesInFlight) completed_ = std::max(completed_, frame_ - caps_.framesInFlight);
        FrameTimestamps& t = slotFor(frame_);
        t.frame = frame_;
        std::fill(t.ns.begin(), t.ns.end(), 0);
        return list_;
    }
    void endFrame(TextureHandle present) override {
        if (!inFrame_) throw Error("endFrame() without beginFrame()");
        if (present) textures.get(present);
        inFrame_ = false;
        lastFrame_ = list_.counts();
    }
    uint64_t frameIndex() const override { return frame_; }
    CommandCounts frameCounters() const override { return lastFrame_; }
    bool readTimestamps(uint64_t frame, std::span<uint64_t> out) override {
        const FrameTimestamps& t = slotFor(frame);
        if (t.frame != frame || frame > completed_) return false;
        if (out.size() > t.ns.size()) throw Error("readTimestamps: more slots than maxTimestampsPerFrame");
        std::copy_n(t.ns.begin(), out.size(), out.begin());
        return true;
    }
    void waitIdle() override { completed_ = inFrame_ ? frame_ - 1 : frame_; }

    void tick() { clockNs_ += 1000; }
    void writeTimestamp(uint32_t slot) {
        if (!inFrame_) throw Error("writeTimestamp outside a frame");
        FrameTimestamps& t = slotFor(frame_);
        if (slot >= t.ns.size())
            throw Error("timestamp slot " + std::to_string(slot) + " >= maxTimestampsPerFrame " +
                        std::to_string(t.ns.size()));
        t.ns[slot] = clockNs_;
    }
    const AllocationRecord& allocations() const override { return allocations_; }

    HandlePool<BufferTag, NullBuffer> buffers;
    HandlePool<TextureTag, NullTexture> textures;
    HandlePool<SamplerTag, NullSampler> samplers;
    HandlePool<GraphicsPipelineTag, NullGraphicsPipeline> graphicsPipelines;
    HandlePool<ComputePipelineTag, NullComputePipeline> computePipelines;

private:
    static void checkRange(const NullBuffer& b, uint64_t offset, uint64_t size) {
        if (offset + size > b.desc.size)
            throw Error("buffer '" + b.desc.debugName + "': range [" + std::to_string(offset) + ", " +
                        std::to_string(offset + size) + ") exceeds its size " + std::to_string(b.desc.size));
    }

    struct FrameTimestamps {
        uint64_t frame = 0;
        std::vector<uint64_t> ns;
    };
    FrameTimestamps& slotFor(uint64_t frame) { return timestamps_[frame % timestamps_.size()]; }
    const FrameTimestamps& slotFor(uint64_t frame) const { return timestamps_[frame % timestamps_.size()]; }

    Caps caps_;
    AllocationRecord allocations_;
    std::vector<FrameTimestamps> timestamps_;
    uint64_t completed_ = 0;
    uint64_t clockNs_ = 1000000;
    NullCommandList list_;
    CommandCounts lastFrame_;
    uint64_t frame_ = 0;
    bool inFrame_ = false;
};

void NullCommandList::requirePass(bool inside, const char* what) const {
    device_.tick();
    if (inPass_ != inside)
        throw Error(std::string(what) + (inside ? " outside a render pass" : " inside a render pass"));
}

void NullCommandList::writeTimestamp(uint32_t slot) {
    device_.writeTimestamp(slot);
}

void NullCommandList::beginRenderPass(const RenderPassDesc& desc) {
    requirePass(false, "beginRenderPass");
    isLayeredPass(desc, device_.caps());
    for (uint32_t i = 0; i < desc.colorCount; ++i)
        device_.textures.get(desc.colors[i].texture);
    if (desc.depth.texture) device_.textures.get(desc.depth.texture);
    inPass_ = true;
}
void NullCommandList::bindPipeline(GraphicsPipelineHandle p) {
    device_.graphicsPipelines.get(p);
}
void NullCommandList::bindPipeline(ComputePipelineHandle p) {
    device_.computePipelines.get(p);
}
void NullCommandList::bindVertexBuffer(uint32_t, BufferHandle b, uint64_t) {
    device_.buffers.get(b);
}
void NullCommandList::bindIndexBuffer(BufferHandle b, IndexType, uint64_t) {
    device_.buffers.get(b);
}
void NullCommandList::bindUniformBuffer(uint32_t, BufferHandle b, uint64_t, uint64_t) {
    device_.buffers.get(b);
}
void NullCommandList::bindStorageBuffer(uint32_t, BufferHandle b, uint64_t, uint64_t) {
    device_.buffers.get(b);
}
void NullCommandList::bindTexture(uint32_t, TextureHandle t, SamplerHandle s) {
    device_.textures.get(t);
    device_.samplers.get(s);
}
void NullCommandList::bindStorageImage(uint32_t binding, TextureHandle t, uint32_t) {
    validateStorageImageBinding(binding, device_.caps(), "bindStorageImage");
    device_.textures.get(t);
}
void NullCommandList::clearTexture(TextureHandle t, const std::array<float, 4>&) {
    requirePass(false, "clearTexture");
    device_.textures.get(t);
    ++counts_.barriers;
}
void NullCommandList::updateBuffer(BufferHandle b, uint64_t offset, const void* data, uint32_t size) {
    requirePass(false, "updateBuffer");
    device_.uploadBuffer(b, offset, data, size);
    counts_.barriers += 2;
}
void NullCommandList::copyTextures(std::span<const TextureCopy> copies) {
    requirePass(false, "copyTextures");
    validateTextureCopies(
        copies, [&](TextureHandle t) -> const TextureDesc& { return device_.textures.get(t).desc; });
    ++counts_.barriers;
}

} // namespace

std::unique_ptr<Device> createNullDevice(const DeviceConfig& config) {
    return std::make_unique<NullDevice>(config);
}

} // namespace lpv::rhi
