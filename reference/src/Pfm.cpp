// PFM and EXR files of the reference's images. Writing goes through the engine's HDR writer (one
// PFM encoder in the tree, and its checked file writes); reading is here, for cached references.
#include "reference/Pfm.h"

#include "engine/ImageFile.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace lpv::reference {
namespace {

std::vector<float> rgba(uint32_t width, uint32_t height, std::span<const glm::vec3> pixels,
                        const std::string& path) {
    if (pixels.size() != size_t(width) * height)
        throw std::runtime_error(path + ": pixel data does not match " + std::to_string(width) + "x" +
                                 std::to_string(height));
    std::vector<float> out(pixels.size() * 4, 1.0f);
    for (size_t i = 0; i < pixels.size(); ++i)
        for (size_t c = 0; c < 3; ++c)
            out[i * 4 + c] = pixels[i][int(c)];
    return out;
}

} // namespace

void writePfm(const std::string& path, uint32_t width, uint32_t height, std::span<const glm::vec3> pixels) {
    if (engine::imageFormatOf(path) != engine::ImageFormat::Pfm)
        throw std::runtime_error(path + ": a PFM file must end in .pfm");
    engine::writeHdr(path, width, height, rgba(width, height, pixels, path));
}

void writeExr(const std::string& path, uint32_t width, uint32_t height, std::span<const glm::vec3> pixels) {
    if (engine::imageFormatOf(path) != engine::ImageFormat::Exr)
        throw std::runtime_error(path + ": an EXR file must end in .exr");
    engine::writeHdr(path, width, height, rgba(width, height, pixels, path));
}

PfmImage readPfm(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot open " + path);
    const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    const auto fail = [&](const std::string& problem) { return std::runtime_error(path + ": " + problem); };

    // Three whitespace-separated header fields after the magic, then exactly one whitespace byte.
    size_t at = 0;
    const auto token = [&]() {
        while (at < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[at])))
            ++at;
        const size_t start = at;
        while (at < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[at])))
            ++at;
        return bytes.substr(start, at - start);
    };
    const std::string magic = token();
    if (magic != "PF" && magic != "Pf") throw fail("not a PFM file (magic '" + magic.substr(0, 8) + "')");
    const size_t channels = magic == "PF" ? 3 : 1;
    long width = 0, height = 0;
    double scale = 0.0;
    try {
        width = std::stol(token());
        height = std::stol(token());
        scale = std::stod(token());
    } catch (const std::exception&) {
        throw fail("malformed PFM header");
    }
    if (width <= 0 || height <= 0 || width > 65536 || height > 65536 || scale == 0.0 || std::isnan(scale))
        throw fail("malformed PFM header");
    ++at; // the single whitespace byte before the data
    const size_t count = size_t(width) * size_t(height);
    if (bytes.size() < at + count * channels * sizeof(float))
        throw fail("truncated: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                   std::to_string(count * channels * sizeof(float)) + " bytes of data");
    // Negative scale: little endian.
    const bool swap = (scale < 0.0) != (std::endian::native == std::endian::little);

    PfmImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.pixels.resize(count);
    const char* data = bytes.data() + at;
    for (size_t row = 0; row < size_t(height); ++row) {
        const size_t y = size_t(height) - 1 - row; // the file's first row is the bottom
        for (size_t x = 0; x < size_t(width); ++x)
            for (size_t c = 0; c < 3; ++c) {
                uint32_t bits;
                std::memcpy(&bits,
                            data + ((row * size_t(width) + x) * channels + (channels == 3 ? c : 0)) * 4, 4);
                if (swap) bits = __builtin_bswap32(bits);
                image.pixels[y * size_t(width) + x][int(c)] = std::bit_cast<float>(bits);
            }
    }
    return image;
}

} // namespace lpv::reference
