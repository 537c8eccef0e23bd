// The device: creates resources and pipelines, runs frames, reads results back. This header,
// with the ones it includes, is all the rest of the engine sees of a graphics API.
#pragma once

#include "rhi/AllocationRecord.h"
#include "rhi/Backend.h"
#include "rhi/CommandList.h"
#include "rhi/Handle.h"
#include "rhi/Pipeline.h"
#include "rhi/Resources.h"
#include "rhi/Shader.h"

#include <cstdint>
#include <span>
#include <string>

namespace lpv::rhi {

// Where GPU timestamps come from. Consumers must show this next to every figure.
enum class TimestampSource : uint8_t {
    None,        // no timing at all
    GpuQueries,  // device timestamps (Vulkan queries, GL_TIMESTAMP): accurate, no stall
    CpuFinished, // fallback: the CPU clock read after waiting for all prior GPU work
                 // (glFinish). Serializes the GPU at every timestamp, so frame totals grow.
    Simulated,   // null backend: 1 us per recorded command, ready framesInFlight frames later,
                 // so front-end code can be tested on the same latency rules as a real device
};
std::string_view timestampSourceName(TimestampSource s);

struct Caps {
    std::string deviceName;
    std::string driverName;
    TimestampSource timestampSource = TimestampSource::None;
    uint32_t maxTimestampsPerFrame = 0;
    uint32_t framesInFlight = 2;
    uint32_t max3DTextureSize = 0;
    uint32_t max2DTextureSize = 0;
    uint32_t maxColorTargets = 0;
    bool presentation = false; // a window surface is attached and endFrame() presents
    // False on the null device, which records commands and draws nothing: what it reads back is
    // zeros, so a screenshot from it is black.
    bool drawsPixels = true;
    // How many compute workgroups the device runs at once, where that is small enough to plan
    // for: a CPU rasterizer (lavapipe, llvmpipe) runs one per host thread, so kernels there want
    // few, long-running workgroups. 0 on GPUs: many, size the dispatch for occupancy.
    uint32_t concurrentWorkgroups = 0;
    // A vertex shader may pick the layer (gl_Layer) of a layered render pass: one draw fills
    // every slice of a volume (Vulkan shaderOutputLayer, GL_ARB_shader_viewport_layer_array).
    bool vertexShaderLayer = false;
    // A shader pays for both sides of every branch, whatever its lanes take, inactive ones masked:
    // Mesa 22.3's llvmpipe and lavapipe compile shaders that way (an early return or discard saved
    // nothing in a measured fullscreen pass), while a fragment block that fails the depth test is
    // skipped. Work chosen per pixel is then better split into passes a depth test selects. False
    // on GPUs, where a branch no lane of a wave takes costs next to nothing.
    bool maskedBranches = false;
    // A fragment shader may write the stencil value (gl_FragStencilRefARB; Vulkan
    // VK_EXT_shader_stencil_export, GL_ARB_shader_stencil_export): one pass can store a different
    // stencil per pixel.
    bool shaderStencilExport = false;
    // CommandList::drawIndexedIndirect with many draws and first instances other than 0 (Vulkan's
    // multiDrawIndirect and drawIndirectFirstInstance features; GL 4.3's glMultiDrawElementsIndirect).
    bool multiDrawIndirect = false;
    // A fragment shader may store to storage images (Vulkan's fragmentStoresAndAtomics; core in GL
    // 4.2): a draw can write a volume through its fragments.
    bool fragmentStores = false;
    // Storage images take bindings below this (rhi/Shader.h): OpenGL's image units and per-stage
    // image uniforms (8 on NVIDIA's driver, the spec's minimum; 32 on Mesa), Vulkan's per-stage
    // storage images, at most the 32 bindings the command lists track.
    uint32_t storageImageBindings = kPortableStorageImageBindings;
    // Sampled textures a fragment shader may bind, at bindings below this: OpenGL's texture units
    // (GL_MAX_TEXTURE_IMAGE_UNITS, 16 at the spec's minimum, 32 on Mesa and NVIDIA), Vulkan's
    // per-stage samplers and sampled images.
    uint32_t fragmentTextureBindings = 16;
    // The same for a compute shader: OpenGL's GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS (16 at the spec's
    // minimum, 32 on Mesa and NVIDIA), Vulkan's per-stage limits as above.
    uint32_t computeTextureBindings = 16;
};

class Device {
public:
    virtual ~Device() = default;
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    virtual BackendKind backend() const = 0;
    virtual const Caps& caps() const = 0;

    virtual BufferHandle createBuffer(const BufferDesc& desc, const void* initialData = nullptr) = 0;
    virtual TextureHandle createTexture(const TextureDesc& desc) = 0;
    virtual SamplerHandle createSampler(const SamplerDesc& desc) = 0;
    virtual GraphicsPipelineHandle createPipeline(const GraphicsPipelineDesc& desc) = 0;
    virtual ComputePipelineHandle createPipeline(const ComputePipelineDesc& desc) = 0;

    // Destroying waits until no frame in flight can still use the resource.
    virtual void destroy(BufferHandle h) = 0;
    virtual void destroy(TextureHandle h) = 0;
    virtual void destroy(SamplerHandle h) = 0;
    virtual void destroy(GraphicsPipelineHandle h) = 0;
    virtual void destroy(ComputePipelineHandle h) = 0;

    virtual const BufferDesc& desc(BufferHandle h) const = 0;
    virtual const TextureDesc& desc(TextureHandle h) const = 0;

    // Immediate transfers, for load time and tests: they wait for the GPU, so call them outside
    // beginFrame()/endFrame() and never in a steady-state frame.
    virtual void uploadBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) = 0;
    // All layers/slices of one mip level, tightly packed.
    virtual void uploadTexture(TextureHandle h, uint32_t mipLevel, const void* data, uint64_t size) = 0;
    virtual void readBuffer(BufferHandle h, uint64_t offset, void* out, uint64_t size) = 0;
    virtual void readTexture(TextureHandle h, uint32_t mipLevel, void* out, uint64_t size) = 0;
    // CPU pointer of a MemoryAccess::HostWrite or HostRead buffer. Writes must not touch data a
    // frame in flight still uses (keep one region per frame in flight).
    virtual void* mapped(BufferHandle h) = 0;

    // Frames. beginFrame() waits until the oldest frame in flight has finished on the GPU, then
    // returns the command list for the new frame. endFrame() submits it and, with a window,
    // presents `present` (an RGBA8 color-target texture, row 0 at the top) scaled to the window.
    virtual CommandList& beginFrame() = 0;
    virtual void endFrame(TextureHandle present = {}) = 0;
    // Index of the frame last begun (0 before the first beginFrame()).
    virtual uint64_t frameIndex() const = 0;
    // Commands the last ended frame recorded (CommandList::counts()), endFrame()'s own included.
    virtual CommandCounts frameCounters() const = 0;
    // Timestamps written in `frame`, in nanoseconds on one clock. Returns false without waiting
    // when that frame's results are not ready yet or no longer kept (kept for framesInFlight + 1
    // frames after they are written).
    virtual bool readTimestamps(uint64_t frame, std::span<uint64_t> nanoseconds) = 0;
    virtual void waitIdle() = 0;

    virtual const AllocationRecord& allocations() const = 0;

protected:
    Device() = default;
};

} // namespace lpv::rhi
