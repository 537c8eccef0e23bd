// Writing frames to disk: 8-bit sRGB PNG, or linear HDR as OpenEXR (.exr) or PFM (.pfm).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace lpv::engine {

// RGBA8 pixels, row 0 at the top. Throws std::runtime_error naming the path on failure.
void writePng(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba);
// Linear RGBA float pixels, row 0 at the top; the format follows the extension (.exr or .pfm).
void writeHdr(const std::string& path, uint32_t width, uint32_t height, std::span<const float> rgba);

enum class ImageFormat : uint8_t { Png, Exr, Pfm };
// The format named by the path's extension, in any case. Any other extension (or none) throws
// std::invalid_argument: "unsupported image type '.jpg' (expected .png, .exr or .pfm)".
ImageFormat imageFormatOf(const std::string& path);

} // namespace lpv::engine
