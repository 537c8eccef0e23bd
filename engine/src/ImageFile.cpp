// PNG output through stb_image_write (Debian's libstb ships the implementation).
#include "engine/ImageFile.h"

#include <stb_image_write.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace lpv::engine {

void writePng(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    if (rgba.size() != size_t(width) * height * 4)
        throw std::runtime_error(path + ": pixel data does not match " + std::to_string(width) + "x" +
                                 std::to_string(height) + " RGBA8");
    errno = 0;
    if (!stbi_write_png(path.c_str(), int(width), int(height), 4, rgba.data(), int(width * 4)))
        throw std::runtime_error("cannot write " + path + (errno ? std::string(": ") + std::strerror(errno) : ""));
}

} // namespace lpv::engine
