// Screenshots of a rendered frame: the tone-mapped sRGB output as PNG, or the linear HDR frame
// before tone mapping when the path ends in .exr or .pfm.
#pragma once

#include <string>

namespace lpv::rhi {
class Device;
}

namespace lpv::engine {

class Renderer;

// Reads the frame back (waits for the GPU: not for steady-state frames) and writes `path`, a .png,
// .exr or .pfm (imageFormatOf); throws std::invalid_argument for another type.
void writeScreenshot(rhi::Device& device, const Renderer& renderer, const std::string& path);

} // namespace lpv::engine
