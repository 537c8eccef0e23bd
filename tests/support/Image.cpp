// Readback of textures in any test format into float images.
#include "Image.h"

#include <glm/gtc/packing.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace lpv::test {

Image readImage(rhi::Device& device, rhi::TextureHandle texture) {
    const rhi::TextureDesc& d = device.desc(texture);
    Image img;
    img.width = d.width;
    img.height = d.height;
    img.depth = d.depthOrLayers;
    const size_t count = size_t(d.width) * d.height * d.depthOrLayers;
    std::vector<uint8_t> bytes(count * rhi::bytesPerPixel(d.format));
    device.readTexture(texture, 0, bytes.data(), bytes.size());
    img.texels.resize(count);
    for (size_t i = 0; i < count; ++i) {
        glm::vec4& t = img.texels[i];
        switch (d.format) {
        case rhi::Format::RGBA8Unorm:
        case rhi::Format::RGBA8Srgb:
            for (int c = 0; c < 4; ++c)
                t[c] = float(bytes[i * 4 + c]) / 255.0f;
            break;
        case rhi::Format::RGBA16F: {
            uint16_t h[4];
            std::memcpy(h, &bytes[i * 8], 8);
            for (int c = 0; c < 4; ++c)
                t[c] = glm::unpackHalf1x16(h[c]);
            break;
        }
        case rhi::Format::RGBA32F:
            std::memcpy(&t, &bytes[i * 16], 16);
            break;
        case rhi::Format::R32F:
        case rhi::Format::D32F:
            std::memcpy(&t.x, &bytes[i * 4], 4);
            break;
        default:
            throw std::runtime_error("readImage: unsupported format " +
                                     std::string(rhi::formatName(d.format)));
        }
    }
    return img;
}

ImageDifference compareImages(const Image& a, const Image& b, float tolerance) {
    if (a.width != b.width || a.height != b.height || a.depth != b.depth)
        throw std::runtime_error("compareImages: sizes differ");
    ImageDifference diff;
    for (size_t i = 0; i < a.texels.size(); ++i) {
        float m = 0.0f;
        for (int c = 0; c < 4; ++c)
            m = std::max(m, std::fabs(a.texels[i][c] - b.texels[i][c]));
        diff.maxAbs = std::max(diff.maxAbs, m);
        if (m > tolerance) ++diff.texelsOver;
    }
    return diff;
}

std::string describe(glm::vec4 v) {
    std::ostringstream s;
    s << "(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
    return s.str();
}

void checkBackendsAgree(const Image& gl, const Image& vk, const char* what, float fraction) {
    float peak = 0.0f;
    for (const glm::vec4& t : vk.texels)
        peak = std::max({peak, t.r, t.g, t.b});
    REQUIRE(peak > 0.0f);
    const ImageDifference d = compareImages(gl, vk, fraction * peak);
    MESSAGE(std::string(what) << " GL vs Vulkan: max difference " << d.maxAbs << " (peak " << peak << "), "
                              << d.texelsOver << " pixels over " << fraction * peak);
    CHECK(d.texelsOver <= gl.texels.size() / 100);
}

} // namespace lpv::test
