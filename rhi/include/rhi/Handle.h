// Typed, generation-checked resource handles.
//
// A handle is 32 bits: a 16-bit slot index and a 16-bit generation. Destroying a resource bumps
// its slot's generation, so a handle kept past destroy() no longer matches and is reported as
// stale instead of silently aliasing whatever reuses the slot (the sokol / Filament scheme).
#pragma once

#include <cstdint>

namespace lpv::rhi {

template <typename Tag> struct Handle {
    static constexpr uint32_t kInvalid = 0;

    uint32_t bits = kInvalid;

    constexpr bool valid() const { return bits != kInvalid; }
    constexpr explicit operator bool() const { return valid(); }
    constexpr uint32_t index() const { return bits & 0xffffu; }
    // Generation 0 is never handed out, so a default-constructed handle is never valid.
    constexpr uint32_t generation() const { return bits >> 16; }
    static constexpr Handle make(uint32_t index, uint32_t generation) {
        return Handle{(generation << 16) | (index & 0xffffu)};
    }
    friend constexpr bool operator==(Handle a, Handle b) = default;
};

struct BufferTag {
    static constexpr const char* kName = "BufferHandle";
};
struct TextureTag {
    static constexpr const char* kName = "TextureHandle";
};
struct SamplerTag {
    static constexpr const char* kName = "SamplerHandle";
};
struct GraphicsPipelineTag {
    static constexpr const char* kName = "GraphicsPipelineHandle";
};
struct ComputePipelineTag {
    static constexpr const char* kName = "ComputePipelineHandle";
};

using BufferHandle = Handle<BufferTag>;
using TextureHandle = Handle<TextureTag>;
using SamplerHandle = Handle<SamplerTag>;
using GraphicsPipelineHandle = Handle<GraphicsPipelineTag>;
using ComputePipelineHandle = Handle<ComputePipelineTag>;

} // namespace lpv::rhi
