// The volumes' layout and resources.
#include "gi/LpvVolumes.h"

#include <string>

namespace lpv::gi {

uint32_t packedTexelCount(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return 1;
    case ShFormat::Rgba32f:
    case ShFormat::Rgba16f:
        break;
    }
    return 3;
}

bool partialSumShell(const LpvSettings& s) {
    return s.cascades > 1;
}

uint32_t partialSumSize(const LpvSettings& s) {
    const uint32_t n = s.gridSize;
    return partialSumShell(s) ? n + 2 + (n & 1) : n;
}

// Every texel of a format has the same format (the parameter keeps the per-texel question open).
rhi::Format packedTexelFormat(ShFormat f, uint32_t /*texel*/) {
    return f == ShFormat::Rgba16f ? rhi::Format::RGBA16F : rhi::Format::RGBA32UI;
}

LpvVolumes::LpvVolumes(rhi::Device& device, const LpvSettings& settings, bool partialSums)
    : device_(device), settings_(settings) {
    using namespace rhi;
    const uint32_t n = settings.gridSize;
    const Format injectFormat = settings.shFormat == ShFormat::Rgba32f ? Format::RGBA32F : Format::RGBA16F;
    const Format shFormat = shTextureFormat(settings.shFormat);
    const char* channels[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c) {
        const auto volume = [&](Format f, uint32_t usage, const char* what) {
            return device.createTexture({TextureKind::Tex3D, f, n, n, n, 1, usage | kTextureTransfer,
                                         std::string("lpv ") + what + " " + channels[c], "gi.lpv"});
        };
        // Storage too: the propagation kernel reads it with imageLoad, or texelFetch where the
        // device has too few storage image bindings (propagate_body.glsl), and
        // further bounces write their reflected light here (MultipleBounces).
        inject_[size_t(c)] =
            volume(injectFormat, kTextureColorTarget | kTextureSampled | kTextureStorage, "injection");
        accum_[size_t(c)] = volume(shFormat, kTextureStorage | kTextureSampled, "accumulated");
    }
    const uint32_t padded = partialSumSize(settings);
    for (uint32_t t = 0; t < (partialSums ? packedTexelCount(settings.shFormat) : 0); ++t)
        for (uint32_t p = 0; p < 2; ++p)
            partial_[p][t] = device.createTexture(
                {TextureKind::Tex3D, packedTexelFormat(settings.shFormat, t), padded, padded, padded, 1,
                 kTextureStorage | kTextureSampled | kTextureTransfer,
                 std::string(p ? "lpv partial sum pong " : "lpv partial sum ping ") + std::to_string(t),
                 "gi.lpv"});
    if (encoded()) clipping_ = std::make_unique<Rgba8Clipping>(device);
}

LpvVolumes::~LpvVolumes() {
    device_.waitIdle();
    for (const auto* set : {&inject_, &accum_, &partial_[0], &partial_[1]})
        for (rhi::TextureHandle t : *set)
            if (t) device_.destroy(t);
}

bool LpvVolumes::matches(const LpvSettings& s) const {
    return s.gridSize == settings_.gridSize && s.shFormat == settings_.shFormat &&
           s.rgba8Range == settings_.rgba8Range && partialSumShell(s) == partialSumShell(settings_);
}

std::array<rhi::TextureHandle, 3> LpvVolumes::createResult(const std::string& name) const {
    using namespace rhi;
    const uint32_t n = settings_.gridSize;
    const char* channels[3] = {"red", "green", "blue"};
    std::array<TextureHandle, 3> out{};
    for (int c = 0; c < 3; ++c)
        out[size_t(c)] = device_.createTexture({TextureKind::Tex3D, shTextureFormat(settings_.shFormat), n, n,
                                                n, 1, kTextureStorage | kTextureSampled | kTextureTransfer,
                                                name + " " + channels[c], "gi.lpv"});
    return out;
}

} // namespace lpv::gi
