// Portable float maps (PFM), the format reference images are cached in: "PF\n<w> <h>\n-1.0\n" then
// little-endian RGB floats, rows bottom to top. In memory, row 0 is the top, as everywhere else.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lpv::reference {

struct PfmImage {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> pixels; // row 0 at the top
};

// Throws std::runtime_error naming the path on failure.
void writePfm(const std::string& path, uint32_t width, uint32_t height, std::span<const glm::vec3> pixels);
// Reads colour ("PF") and greyscale ("Pf", copied to all three channels) maps of either byte order.
// Throws std::runtime_error naming the path and the problem.
PfmImage readPfm(const std::string& path);

// The same pixels as OpenEXR (RGB float, through the engine's writer).
void writeExr(const std::string& path, uint32_t width, uint32_t height, std::span<const glm::vec3> pixels);

} // namespace lpv::reference
