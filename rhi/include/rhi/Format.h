// Pixel formats, texture kinds and usage flags the engine can ask for, independent of any API.
#pragma once

#include <cstdint>
#include <string_view>

namespace lpv::rhi {

enum class Format : uint8_t {
    Undefined,
    RGBA8Unorm,
    RGBA8Srgb,
    RGBA16F,
    RGBA32F,
    RG16F,
    R32F,
    R32UI,
    RG32UI,   // packed data (e.g. pairs of halves), no filtering
    RGBA32UI, // packed data, no filtering
    D32F,
    // Depth and an 8-bit stencil: a depth target only (never sampled, stored or transferred).
    D32FS8,
};

enum class TextureKind : uint8_t { Tex2D, Tex2DArray, Tex3D };

// Bit flags: what a texture will be used for. Backends pick layouts and memory from these.
enum TextureUsage : uint32_t {
    kTextureSampled = 1u << 0,
    kTextureStorage = 1u << 1,     // image load/store from shaders
    kTextureColorTarget = 1u << 2, // render target; a 3D or array texture renders per slice
    kTextureDepthTarget = 1u << 3,
    kTextureTransfer = 1u << 4, // upload, clear, copy and readback
};

uint32_t bytesPerPixel(Format f);
bool isDepthFormat(Format f);
// Depth formats that also hold a stencil.
bool hasStencil(Format f);
// Unsigned-integer formats: read and written as uint, never filtered, cleared with integer values.
bool isIntegerFormat(Format f);
std::string_view formatName(Format f);

} // namespace lpv::rhi
