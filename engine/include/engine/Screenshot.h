// Screenshots of a rendered frame: the tone-mapped sRGB output as PNG, or the linear HDR frame
// before tone mapping when the path ends in .exr or .pfm.
#pragma once

#include <string>
#include <vector>

namespace lpv::rhi {
class Device;
}

namespace lpv::engine {

class Renderer;

// The frame's linear HDR pixels before tone mapping, RGBA floats, row 0 at the top (waits for the
// GPU: not for steady-state frames).
std::vector<float> readHdrFrame(rhi::Device& device, const Renderer& renderer);

// Reads the frame back (waits for the GPU: not for steady-state frames) and writes `path`, a .png,
// .exr or .pfm (imageFormatOf); throws std::invalid_argument for another type.
void writeScreenshot(rhi::Device& device, const Renderer& renderer, const std::string& path);

} // namespace lpv::engine
