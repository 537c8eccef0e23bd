// Format facts shared by the backends and the allocation record.
#include "rhi/Format.h"
#include "rhi/Resources.h"

#include <algorithm>

namespace lpv::rhi {

uint32_t bytesPerPixel(Format f) {
    switch (f) {
    case Format::RGBA8Unorm:
    case Format::RGBA8Srgb:
    case Format::RG16F:
    case Format::R32F:
    case Format::R32UI:
    case Format::D32F:
        return 4;
    case Format::RGBA16F:
        return 8;
    case Format::RG32UI:
    case Format::D32FS8: // as Vulkan and GL lay it out: 32 bits of depth, 8 of stencil, 24 unused
        return 8;
    case Format::RGBA32F:
    case Format::RGBA32UI:
        return 16;
    case Format::Undefined:
        return 0;
    }
    return 0;
}

bool isDepthFormat(Format f) {
    return f == Format::D32F || f == Format::D32FS8;
}

bool hasStencil(Format f) {
    return f == Format::D32FS8;
}

bool isIntegerFormat(Format f) {
    return f == Format::R32UI || f == Format::RG32UI || f == Format::RGBA32UI;
}

std::string_view formatName(Format f) {
    switch (f) {
    case Format::Undefined:
        return "undefined";
    case Format::RGBA8Unorm:
        return "rgba8";
    case Format::RGBA8Srgb:
        return "rgba8_srgb";
    case Format::RGBA16F:
        return "rgba16f";
    case Format::RGBA32F:
        return "rgba32f";
    case Format::RG16F:
        return "rg16f";
    case Format::R32F:
        return "r32f";
    case Format::R32UI:
        return "r32ui";
    case Format::RG32UI:
        return "rg32ui";
    case Format::RGBA32UI:
        return "rgba32ui";
    case Format::D32F:
        return "d32f";
    case Format::D32FS8:
        return "d32f_s8";
    }
    return "?";
}

uint64_t textureBytes(const TextureDesc& d) {
    uint64_t total = 0;
    uint64_t w = d.width, h = d.height, z = d.depthOrLayers;
    for (uint32_t mip = 0; mip < d.mipLevels; ++mip) {
        total += w * h * z * bytesPerPixel(d.format);
        w = std::max<uint64_t>(1, w / 2);
        h = std::max<uint64_t>(1, h / 2);
        if (d.kind == TextureKind::Tex3D) z = std::max<uint64_t>(1, z / 2);
    }
    return total;
}

} // namespace lpv::rhi
