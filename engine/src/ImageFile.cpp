// Image output: PNG through stb_image_write, EXR through tinyexr, PFM written directly (a header
// line and raw floats - there is no library for it among the project's packages). Each is encoded
// in memory and written by Platform::writeFile, which checks every step of the write.
#include "engine/ImageFile.h"

#include "platforms/Platform.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

namespace lpv::engine {

ImageFormat imageFormatOf(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension == ".png") return ImageFormat::Png;
    if (extension == ".exr") return ImageFormat::Exr;
    if (extension == ".pfm") return ImageFormat::Pfm;
    throw std::invalid_argument(
        (extension.empty() ? std::string("no image type") : "unsupported image type '" + extension + "'") +
        " (expected .png, .exr or .pfm)");
}

void writePng(const std::string& path, uint32_t width, uint32_t height, std::span<const uint8_t> rgba) {
    if (rgba.size() != size_t(width) * height * 4)
        throw std::runtime_error(path + ": pixel data does not match " + std::to_string(width) + "x" +
                                 std::to_string(height) + " RGBA8");
    // Encoded in memory and written here: stbi_write_png ignores fwrite and fclose errors, so a
    // full disk would pass for success.
    std::string png;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    if (!stbi_write_png_to_func(append, &png, int(width), int(height), 4, rgba.data(), int(width * 4)))
        throw std::runtime_error("cannot write " + path + ": PNG encoding failed");
    platforms::Platform::writeFile(path, png);
}

void writeHdr(const std::string& path, uint32_t width, uint32_t height, std::span<const float> rgba) {
    if (rgba.size() != size_t(width) * height * 4)
        throw std::runtime_error(path + ": pixel data does not match " + std::to_string(width) + "x" +
                                 std::to_string(height) + " RGBA float");
    const ImageFormat format = imageFormatOf(path);
    if (format == ImageFormat::Exr) {
        // What SaveEXR does, but encoded in memory and written here: SaveEXR does not check fclose,
        // so a full disk passed for success. RGB at full float precision (the indirect-light view is
        // compared against a path tracer), channels in the B, G, R order viewers expect.
        const size_t count = size_t(width) * height;
        std::vector<float> planes[3];
        for (size_t c = 0; c < 3; ++c) {
            planes[c].resize(count);
            for (size_t i = 0; i < count; ++i)
                planes[c][i] = rgba[i * 4 + c];
        }
        float* bgr[3] = {planes[2].data(), planes[1].data(), planes[0].data()};
        EXRImage image;
        InitEXRImage(&image);
        image.num_channels = 3;
        image.images = reinterpret_cast<unsigned char**>(bgr);
        image.width = int(width);
        image.height = int(height);
        EXRChannelInfo channels[3] = {};
        channels[0].name[0] = 'B';
        channels[1].name[0] = 'G';
        channels[2].name[0] = 'R';
        int pixelTypes[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
        EXRHeader header;
        InitEXRHeader(&header);
        header.compression_type =
            width < 16 && height < 16 ? TINYEXR_COMPRESSIONTYPE_NONE : TINYEXR_COMPRESSIONTYPE_ZIP;
        header.num_channels = 3;
        header.channels = channels;
        header.pixel_types = pixelTypes;
        header.requested_pixel_types = pixelTypes;
        unsigned char* memory = nullptr;
        const char* err = nullptr;
        const size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
        const std::unique_ptr<unsigned char, decltype(&std::free)> owned(memory, &std::free);
        if (size == 0) {
            const std::string message = err ? err : "unknown error";
            FreeEXRErrorMessage(err);
            throw std::runtime_error("cannot write " + path + ": EXR encoding failed: " + message);
        }
        platforms::Platform::writeFile(path, std::string_view(reinterpret_cast<const char*>(memory), size));
        return;
    }
    if (format != ImageFormat::Pfm)
        throw std::runtime_error(path + ": HDR screenshots must end in .exr or .pfm");
    // PFM: "PF", size, negative scale = little endian; rows run bottom to top.
    std::string pfm = "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    std::vector<float> row(size_t(width) * 3);
    for (uint32_t y = height; y-- > 0;) {
        for (uint32_t x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c)
                row[size_t(x) * 3 + size_t(c)] = rgba[(size_t(y) * width + x) * 4 + size_t(c)];
        pfm.append(reinterpret_cast<const char*>(row.data()), row.size() * sizeof(float));
    }
    platforms::Platform::writeFile(path, pfm);
}

} // namespace lpv::engine
