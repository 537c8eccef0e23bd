// Recording of GPU work for one frame. Record, then submit: the Vulkan backend records into a
// VkCommandBuffer, the GL backend replays the same commands on its context at submit.
//
// Barriers are the RHI's job, not the caller's: every texture has a home state derived from its
// usage, render passes and transfers move it out and back (a storage image stays in its one state:
// Vulkan's GENERAL), and a barrier makes each command's writes visible to the later commands that
// need them and orders it before them (what lets a storage image skip the moves). It is paid only
// at a hazard, in one call with the next command's own:
// - Vulkan: the barrier of a dispatch, of a clear of a storage image and of a buffer update is owed:
//   recorded before the next dispatch or transfer that reads or writes what it wrote (or writes
//   what it read: storage images and buffers a shader does not declare readonly count as written,
//   the others and sampled textures and uniform buffers as read), and before any render pass, in the
//   same vkCmdPipelineBarrier2 as that command's own when it has one. Where the device keeps every
//   texture in GENERAL (unified image layouts: a CPU device, or VK_KHR_unified_image_layouts), a
//   render pass begins at its first draw, behind a barrier only where its targets or what that
//   draw binds meet a hazard (a later draw that meets one stops the pass for it), and its targets
//   are owed like a dispatch's writes. Otherwise it moves its targets to their attachment
//   layouts and owes its barrier (its targets back home, its writes visible) to the next command.
// - GL: a command pays one glMemoryBarrier, with the bits of its own accesses, where it touches
//   what earlier shaders stored to or stores to what they read (GlHazards.h); GL orders
//   everything else itself.
// DeviceConfig::conservativeBarriers (or LPV_CONSERVATIVE_BARRIERS=1) restores a barrier after
// every dispatch, render pass and transfer, to rule a synchronization bug in or out in one run.
// The rule keeps the validation layer, synchronization validation included, silent.
#pragma once

#include "rhi/Handle.h"

#include <array>
#include <cstdint>
#include <limits>
#include <span>

namespace lpv::rhi {

enum class LoadOp : uint8_t { Load, Clear, DontCare };
enum class IndexType : uint8_t { Uint16, Uint32 };

struct ColorAttachment {
    TextureHandle texture;
    uint32_t mipLevel = 0;
    uint32_t layer = 0; // array layer, or slice of a 3D texture
    LoadOp load = LoadOp::Clear;
    std::array<float, 4> clearColor{0.0f, 0.0f, 0.0f, 0.0f};
    // Every layer (slice) of the mip at once; the vertex shader writes gl_Layer. Needs
    // Caps::vertexShaderLayer, all colour targets layered with equal layer counts, and no depth.
    bool layered = false;
};

struct DepthAttachment {
    TextureHandle texture;
    uint32_t layer = 0;
    LoadOp load = LoadOp::Clear;
    float clearDepth = 1.0f;
    uint8_t clearStencil = 0; // formats with a stencil (hasStencil)
};

struct RenderPassDesc {
    static constexpr uint32_t kMaxColorTargets = 8;
    std::array<ColorAttachment, kMaxColorTargets> colors{};
    uint32_t colorCount = 0;
    DepthAttachment depth{}; // texture left invalid: no depth
    const char* debugName = "render pass";
};

struct Viewport {
    float x = 0, y = 0, width = 0, height = 0;
    float minDepth = 0.0f, maxDepth = 1.0f;
};

inline constexpr uint64_t kWholeSize = std::numeric_limits<uint64_t>::max();

// One draw of drawIndexedIndirect(), as Vulkan's VkDrawIndexedIndirectCommand and GL's
// DrawElementsIndirectCommand lay it out.
struct DrawIndexedIndirectCommand {
    uint32_t indexCount = 0;
    uint32_t instanceCount = 1;
    uint32_t firstIndex = 0;
    int32_t vertexOffset = 0;
    uint32_t firstInstance = 0;
};
static_assert(sizeof(DrawIndexedIndirectCommand) == 20);

// Commands recorded, counted as the backend issues them to its API: on Vulkan vkCmdDispatch,
// vkCmdDraw, vkCmdDrawIndexed, vkCmdDrawIndexedIndirect and vkCmdPipelineBarrier2 calls (a split
// point list is several draws); on GL glDispatchCompute, the glDraw* and glMultiDraw* calls and
// glMemoryBarrier calls (an indirect multi-draw counts once, as an indexed draw); on the null device
// what the Vulkan backend's rule would record. Snapshots subtract: counts at a pass's end minus
// counts at its begin are the pass's.
struct CommandCounts {
    uint32_t dispatches = 0;
    uint32_t draws = 0;        // not indexed
    uint32_t drawsIndexed = 0; // drawIndexed and drawIndexedIndirect calls
    uint32_t barriers = 0;
    // Serial stages: runs of dispatches and draws with no barrier between them, counted at each
    // run's first command. Work in one stage may overlap on a GPU; a barrier ends the stage (even
    // one that orders unrelated resources). Over a scope: the length of its chain of dependent
    // passes, as recorded.
    uint32_t stages = 0;

    uint32_t allDraws() const { return draws + drawsIndexed; }
    CommandCounts& operator+=(const CommandCounts& o) {
        dispatches += o.dispatches;
        draws += o.draws;
        drawsIndexed += o.drawsIndexed;
        barriers += o.barriers;
        stages += o.stages;
        return *this;
    }
    friend CommandCounts operator-(CommandCounts a, const CommandCounts& b) {
        a.dispatches -= b.dispatches;
        a.draws -= b.draws;
        a.drawsIndexed -= b.drawsIndexed;
        a.barriers -= b.barriers;
        a.stages -= b.stages;
        return a;
    }
    friend bool operator==(const CommandCounts&, const CommandCounts&) = default;
};

// One texture copied onto another of the same kind, format and size (CommandList::copyTextures).
struct TextureCopy {
    TextureHandle src, dst;
    // Room for an SH volume's three textures in each of four cascades.
    static constexpr size_t kMaxCopies = 12;
};

class CommandList {
public:
    virtual ~CommandList() = default;

    // Render passes. The viewport and scissor are reset to the full first target on begin.
    virtual void beginRenderPass(const RenderPassDesc& desc) = 0;
    virtual void endRenderPass() = 0;
    virtual void setViewport(const Viewport& vp) = 0;
    virtual void setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) = 0;

    virtual void bindPipeline(GraphicsPipelineHandle pipeline) = 0;
    virtual void bindPipeline(ComputePipelineHandle pipeline) = 0;

    virtual void bindVertexBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset = 0) = 0;
    virtual void bindIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset = 0) = 0;

    // Resource bindings by the `binding` number written in the shader. They stay until replaced
    // or until another pipeline is bound.
    virtual void bindUniformBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset = 0,
                                   uint64_t size = kWholeSize) = 0;
    virtual void bindStorageBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset = 0,
                                   uint64_t size = kWholeSize) = 0;
    virtual void bindTexture(uint32_t binding, TextureHandle texture, SamplerHandle sampler) = 0;
    virtual void bindStorageImage(uint32_t binding, TextureHandle texture, uint32_t mipLevel = 0) = 0;
    // Small constants of a pass or a dispatch: copied into a ring the backend owns for this frame
    // and bound as a uniform buffer at `binding`. No allocation: the ring is sized at device
    // creation (DeviceConfig::uniformRingBytes), so it is no place for data that grows with a scene:
    // per-draw records go in a storage buffer, read at the draw's firstInstance (gl_InstanceIndex).
    virtual void pushUniforms(uint32_t binding, const void* data, uint32_t size) = 0;

    virtual void draw(uint32_t vertexCount, uint32_t instanceCount = 1, uint32_t firstVertex = 0,
                      uint32_t firstInstance = 0) = 0;
    virtual void drawIndexed(uint32_t indexCount, uint32_t instanceCount = 1, uint32_t firstIndex = 0,
                             int32_t vertexOffset = 0, uint32_t firstInstance = 0) = 0;
    // `drawCount` indexed draws in one call (Caps::multiDrawIndirect), their parameters the
    // DrawIndexedIndirectCommands at `offset` in `commands`, a MemoryAccess::HostWrite buffer with
    // kBufferIndirect that the CPU wrote before the frame was submitted. The index buffer is bound
    // at offset 0. GL has no per-draw base instance in a vertex shader (gl_InstanceIndex is the
    // first instance of the call), so a multi-drawn pipeline reads what a draw's first instance
    // names from a per-instance vertex attribute, which both APIs offset by it.
    virtual void drawIndexedIndirect(BufferHandle commands, uint64_t offset, uint32_t drawCount) = 0;
    virtual void dispatch(uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1) = 0;

    // Transfers; only outside a render pass.
    virtual void clearTexture(TextureHandle texture, const std::array<float, 4>& value) = 0;
    virtual void updateBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint32_t size) = 0;
    // Same desc, all of mip 0.
    void copyTexture(TextureHandle src, TextureHandle dst) {
        const TextureCopy copy{src, dst};
        copyTextures(std::span(&copy, 1));
    }
    // Up to kMaxCopies copies behind one barrier (each texture in at most one of them).
    virtual void copyTextures(std::span<const TextureCopy> copies) = 0;

    // GPU timestamp `slot` (< Device::caps().maxTimestampsPerFrame) of this frame; read back with
    // Device::readTimestamps some frames later. See Caps::timestampSource for what it measures.
    virtual void writeTimestamp(uint32_t slot) = 0;

    // Debug markers (VK_EXT_debug_utils / KHR_debug) so a capture reads like the code.
    virtual void beginMarker(const char* name) = 0;
    virtual void endMarker() = 0;

    // What this frame recorded so far, from Device::beginFrame() on (the device's own barriers at
    // the frame's start included). Device::frameCounters() has the whole of the last ended frame.
    virtual CommandCounts counts() const { return counts_; }

protected:
    // Backends count into counts_; a dispatch or draw calls countStage with the barriers recorded
    // so far (on any scale that grows by one per barrier).
    void countStage(uint64_t barriersSoFar) {
        if (barriersSoFar != stageBarriers_) {
            ++counts_.stages;
            stageBarriers_ = barriersSoFar;
        }
    }
    void resetCounts() {
        counts_ = {};
        stageBarriers_ = std::numeric_limits<uint64_t>::max();
    }

    CommandCounts counts_;

private:
    uint64_t stageBarriers_ = std::numeric_limits<uint64_t>::max();
};

} // namespace lpv::rhi
