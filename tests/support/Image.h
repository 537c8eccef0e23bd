// Readback images and the comparisons the tests make on them.
#pragma once

#include "rhi/Device.h"

#include <glm/vec4.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace lpv::test {

// A readback converted to floats (RGBA8 -> [0,1], RGBA16F -> float, D32F -> x only).
struct Image {
    uint32_t width = 0, height = 0, depth = 1;
    std::vector<glm::vec4> texels;
    glm::vec4 at(uint32_t x, uint32_t y, uint32_t z = 0) const {
        return texels[(z * height + y) * width + x];
    }
};

Image readImage(rhi::Device& device, rhi::TextureHandle texture);

struct ImageDifference {
    float maxAbs = 0.0f;
    uint32_t texelsOver = 0; // texels whose difference exceeds the tolerance
};
ImageDifference compareImages(const Image& a, const Image& b, float tolerance);

std::string describe(glm::vec4 v);

// The GL and Vulkan images of one lighting term agree: within `fraction` of the brightest value
// (any channel) of `vk`, on all but 1% of the pixels. Checks (doctest) and reports the figures.
void checkBackendsAgree(const Image& gl, const Image& vk, const char* what, float fraction = 0.01f);

} // namespace lpv::test
