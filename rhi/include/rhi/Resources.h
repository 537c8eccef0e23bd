// Plain descriptors for buffers, textures and samplers (NVRHI style): defaulted members, a debug
// name that shows up in RenderDoc and in the allocation record, and the category the frame
// profiler sums memory under (e.g. "gi.lpv", "render.gbuffer").
#pragma once

#include "rhi/Format.h"

#include <cstdint>
#include <string>

namespace lpv::rhi {

enum BufferUsage : uint32_t {
    kBufferVertex = 1u << 0,
    kBufferIndex = 1u << 1,
    kBufferUniform = 1u << 2,
    kBufferStorage = 1u << 3,
    kBufferIndirect = 1u << 4,
    kBufferTransfer = 1u << 5, // upload through updateBuffer/uploadBuffer and readback
};

enum class MemoryAccess : uint8_t {
    GpuOnly,   // device local; written by uploads and shaders
    HostWrite, // persistently mapped for CPU writes (mapped() returns the pointer)
    // Persistently mapped for CPU reads and writes, for what shaders report back (counters, peaks):
    // a frame's shader writes are visible through mapped() once beginFrame() has waited for that
    // frame, framesInFlight frames later. Keep one region per frame in flight, as for HostWrite.
    HostRead,
};

struct BufferDesc {
    uint64_t size = 0;
    uint32_t usage = 0;
    MemoryAccess access = MemoryAccess::GpuOnly;
    std::string debugName;
    std::string category = "misc";
};

struct TextureDesc {
    TextureKind kind = TextureKind::Tex2D;
    Format format = Format::RGBA8Unorm;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t depthOrLayers = 1; // depth for Tex3D, layer count for Tex2DArray
    uint32_t mipLevels = 1;
    uint32_t usage = kTextureSampled;
    std::string debugName;
    std::string category = "misc";
};

enum class Filter : uint8_t { Nearest, Linear };
enum class AddressMode : uint8_t { ClampToEdge, Repeat, ClampToBorderWhite };
enum class CompareOp : uint8_t { Never, Less, LessOrEqual, Greater, GreaterOrEqual, Equal, Always };

struct SamplerDesc {
    Filter minFilter = Filter::Linear;
    Filter magFilter = Filter::Linear;
    Filter mipFilter = Filter::Linear;
    AddressMode address = AddressMode::ClampToEdge;
    float maxAnisotropy = 1.0f;
    // Depth-compare sampling (shadow maps): the shader uses a sampler*Shadow and gets filtered
    // comparison results.
    bool compareEnable = false;
    CompareOp compareOp = CompareOp::LessOrEqual;
    std::string debugName;
};

// Size in bytes of one mip chain of a texture, the figure the allocation record uses when a
// backend cannot ask its driver.
uint64_t textureBytes(const TextureDesc& desc);

} // namespace lpv::rhi
