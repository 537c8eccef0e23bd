// Uploads the specular albedo table.
#include "engine/render/SpecularAlbedoTexture.h"

#include "engine/render/SpecularAlbedo.h"

#include <glm/packing.hpp>

#include <vector>

namespace lpv::engine {

SpecularAlbedoTexture::SpecularAlbedoTexture(rhi::Device& device) : device_(device) {
    const SpecularAlbedoTable& table = specularAlbedoTable();
    constexpr uint32_t n = SpecularAlbedoTable::kSize;
    // Block 0: scale, bias, scaleDirection; block 1: biasDirection, the Schlick mean (the same in
    // every row: it does not depend on roughness) (shaders/specular_albedo.glsl).
    std::vector<uint32_t> halves(size_t(n) * n * 2 * 2);
    for (size_t i = 0; i < table.texels.size(); ++i) {
        const SpecularAlbedo& t = table.texels[i];
        halves[2 * i] = glm::packHalf2x16({t.scale, t.bias});
        halves[2 * i + 1] = glm::packHalf2x16(t.scaleDirection);
        halves[2 * (table.texels.size() + i)] = glm::packHalf2x16(t.biasDirection);
        halves[2 * (table.texels.size() + i) + 1] = glm::packHalf2x16({table.schlickMean[i % n], 0.0f});
    }
    texture_ = device.createTexture({rhi::TextureKind::Tex2D, rhi::Format::RGBA16F, n, 2 * n, 1, 1,
                                     rhi::kTextureSampled | rhi::kTextureTransfer, "specular albedo",
                                     "render.lighting"});
    device.uploadTexture(texture_, 0, halves.data(), halves.size() * sizeof(uint32_t));
}

SpecularAlbedoTexture::~SpecularAlbedoTexture() {
    device_.waitIdle();
    device_.destroy(texture_);
}

} // namespace lpv::engine
