// Reading the renderer's targets back for screenshots.
#include "engine/Screenshot.h"

#include "engine/ImageFile.h"
#include "engine/render/Renderer.h"

#include <glm/gtc/packing.hpp>

#include <cstring>
#include <vector>

namespace lpv::engine {

std::vector<float> readHdrFrame(rhi::Device& device, const Renderer& renderer) {
    device.waitIdle();
    std::vector<uint16_t> half(size_t(renderer.width()) * renderer.height() * 4);
    device.readTexture(renderer.hdr(), 0, half.data(), half.size() * sizeof(uint16_t));
    std::vector<float> rgba(half.size());
    for (size_t i = 0; i < half.size(); ++i)
        rgba[i] = glm::unpackHalf1x16(half[i]);
    return rgba;
}

void writeScreenshot(rhi::Device& device, const Renderer& renderer, const std::string& path) {
    const uint32_t w = renderer.width(), h = renderer.height();
    // Before the read-back: an unsupported type is refused, never written as PNG.
    const ImageFormat format = imageFormatOf(path);
    device.waitIdle();
    if (format != ImageFormat::Png) {
        writeHdr(path, w, h, readHdrFrame(device, renderer));
    } else {
        std::vector<uint8_t> rgba(size_t(w) * h * 4);
        device.readTexture(renderer.output(), 0, rgba.data(), rgba.size());
        writePng(path, w, h, rgba);
    }
}

} // namespace lpv::engine
