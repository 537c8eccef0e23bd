// Image output: PNG through stb_image_write, EXR through tinyexr, PFM written directly (a header
// line and raw floats - there is no library for it among the project's packages).
#include "engine/ImageFile.h"

#include "platforms/Platform.h"

#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
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
        const char* err = nullptr;
        // RGB, full float precision: the indirect-light view is compared against a path tracer.
        std::vector<float> rgb(size_t(width) * height * 3);
        for (size_t i = 0; i < size_t(width) * height; ++i)
            for (int c = 0; c < 3; ++c)
                rgb[i * 3 + size_t(c)] = rgba[i * 4 + size_t(c)];
        if (SaveEXR(rgb.data(), int(width), int(height), 3, 0, path.c_str(), &err) < 0) {
            const std::string message = err ? err : "unknown error";
            FreeEXRErrorMessage(err);
            throw std::runtime_error("cannot write " + path + ": " + message);
        }
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
