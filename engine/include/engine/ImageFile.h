// Writing frames to disk: 8-bit sRGB PNG for screenshots.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace lpv::engine {

// RGBA8 pixels, row 0 at the top. Throws std::runtime_error naming the path on failure.
void writePng(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba);

} // namespace lpv::engine
