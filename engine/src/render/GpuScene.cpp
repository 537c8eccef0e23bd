// Uploading a scene: buffers, textures with mips, lights, draw list.
#include "engine/render/GpuScene.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace lpv::engine {
namespace {

// Box-filtered mip chain of an RGBA8 image, all levels packed one after another. sRGB textures
// are averaged in linear space so mips do not darken.
std::vector<uint8_t> mipChain(const TextureImage& image, uint32_t& levels) {
    std::vector<uint8_t> out(image.rgba);
    uint32_t w = image.width, h = image.height;
    levels = 1;
    std::vector<float> lut(256);
    for (int i = 0; i < 256; ++i) {
        const float c = float(i) / 255.0f;
        lut[size_t(i)] =
            image.srgb ? (c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f)) : c;
    }
    const auto encode = [&](float v) {
        v = std::clamp(v, 0.0f, 1.0f);
        if (image.srgb) v = v <= 0.0031308f ? v * 12.92f : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
        return uint8_t(std::lround(v * 255.0f));
    };
    size_t srcOffset = 0;
    while (w > 1 || h > 1) {
        const uint32_t nw = std::max(1u, w / 2), nh = std::max(1u, h / 2);
        const size_t dstOffset = out.size();
        out.resize(dstOffset + size_t(nw) * nh * 4);
        for (uint32_t y = 0; y < nh; ++y)
            for (uint32_t x = 0; x < nw; ++x)
                for (int c = 0; c < 4; ++c) {
                    float sum = 0.0f;
                    for (uint32_t dy = 0; dy < 2; ++dy)
                        for (uint32_t dx = 0; dx < 2; ++dx) {
                            const uint32_t sx = std::min(w - 1, x * 2 + dx), sy = std::min(h - 1, y * 2 + dy);
                            const uint8_t v = out[srcOffset + (size_t(sy) * w + sx) * 4 + size_t(c)];
                            sum += c == 3 ? float(v) / 255.0f : lut[v];
                        }
                    out[dstOffset + (size_t(y) * nw + x) * 4 + size_t(c)] =
                        c == 3 ? uint8_t(std::lround(sum / 4.0f * 255.0f)) : encode(sum / 4.0f);
                }
        srcOffset = dstOffset;
        w = nw;
        h = nh;
        ++levels;
    }
    return out;
}

rhi::TextureHandle solidTexture(rhi::Device& device, const uint8_t rgba[4], rhi::Format format,
                                const char* name) {
    const rhi::TextureHandle t =
        device.createTexture({rhi::TextureKind::Tex2D, format, 1, 1, 1, 1,
                              rhi::kTextureSampled | rhi::kTextureTransfer, name, "scene.textures"});
    device.uploadTexture(t, 0, rgba, 4);
    return t;
}

} // namespace

GpuScene::GpuScene(rhi::Device& device, const Scene& scene) : device_(device) {
    using namespace rhi;
    vertices_ = device.createBuffer({scene.vertices.size() * sizeof(Vertex), kBufferVertex | kBufferTransfer,
                                     MemoryAccess::GpuOnly, scene.name + " vertices", "scene.geometry"},
                                    scene.vertices.data());
    // Levels of detail go after the scene's indices, so one index buffer serves every level.
    std::vector<uint32_t> indices = scene.indices;
    std::vector<std::vector<MeshLod>> meshLods;
    meshLods.reserve(scene.meshes.size());
    for (const Mesh& mesh : scene.meshes)
        meshLods.push_back(simplifyMesh(scene, mesh, indices));
    indices_ = device.createBuffer({indices.size() * sizeof(uint32_t), kBufferIndex | kBufferTransfer,
                                    MemoryAccess::GpuOnly, scene.name + " indices", "scene.geometry"},
                                   indices.data());
    const uint8_t white[4] = {255, 255, 255, 255}, flat[4] = {128, 128, 255, 255};
    white_ = solidTexture(device, white, Format::RGBA8Srgb, "white");
    flatNormal_ = solidTexture(device, flat, Format::RGBA8Unorm, "flat normal");
    for (const TextureImage& image : scene.textures) {
        uint32_t levels = 1;
        const std::vector<uint8_t> chain = mipChain(image, levels);
        const TextureHandle t = device.createTexture(
            {TextureKind::Tex2D, image.srgb ? Format::RGBA8Srgb : Format::RGBA8Unorm, image.width,
             image.height, 1, levels, kTextureSampled | kTextureTransfer, image.name, "scene.textures"});
        size_t offset = 0;
        uint32_t w = image.width, h = image.height;
        for (uint32_t level = 0; level < levels; ++level) {
            const size_t bytes = size_t(w) * h * 4;
            device.uploadTexture(t, level, chain.data() + offset, bytes);
            offset += bytes;
            w = std::max(1u, w / 2);
            h = std::max(1u, h / 2);
        }
        textures_.push_back(t);
    }
    SamplerDesc sd;
    sd.address = AddressMode::Repeat;
    sd.debugName = "material";
    sampler_ = device.createSampler(sd);

    std::vector<GpuPunctualLight> lights;
    for (const Light& l : scene.lights) {
        if (l.type == LightType::Directional) continue;
        GpuPunctualLight g;
        g.positionRange = glm::vec4(l.position, l.range);
        g.colorIntensity = glm::vec4(l.color, l.intensity);
        g.directionType = glm::vec4(glm::normalize(l.direction), l.type == LightType::Spot ? 2.0f : 1.0f);
        g.cone = glm::vec4(std::cos(l.outerConeAngle), std::cos(l.innerConeAngle), 0.0f, 0.0f);
        lights.push_back(g);
    }
    lightCount_ = uint32_t(std::min<size_t>(lights.size(), kMaxPunctualLights));
    lights_ =
        device.createBuffer({sizeof(GpuPunctualLight) * kMaxPunctualLights, kBufferStorage | kBufferTransfer,
                             MemoryAccess::GpuOnly, scene.name + " lights", "scene.lights"});
    if (lightCount_) device.uploadBuffer(lights_, 0, lights.data(), lightCount_ * sizeof(GpuPunctualLight));
    lights.resize(lightCount_);
    lightRecords_ = std::move(lights);

    draws_.reserve(scene.instances.size());
    for (const Instance& inst : scene.instances) {
        const Mesh& mesh = scene.meshes[inst.mesh];
        const Material& mat = scene.materials[mesh.material];
        GpuDraw d;
        d.index = uint32_t(draws_.size());
        d.lods[0] = {mesh.firstIndex, mesh.indexCount, 0.0f};
        // A mesh's error grows with the instance's largest axis scale.
        const glm::mat3 linear(inst.transform);
        const float scale =
            std::max({glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2])});
        for (const MeshLod& lod : meshLods[inst.mesh])
            d.lods[d.lodCount++] = {lod.firstIndex, lod.indexCount, lod.error * scale};
        d.baseColor = mat.baseColorTexture >= 0 ? textures_[size_t(mat.baseColorTexture)] : white_;
        d.normal = mat.normalTexture >= 0 ? textures_[size_t(mat.normalTexture)] : flatNormal_;
        d.metallicRoughnessMap =
            mat.metallicRoughnessTexture >= 0 ? textures_[size_t(mat.metallicRoughnessTexture)] : white_;
        d.emissiveMap = mat.emissiveTexture >= 0 ? textures_[size_t(mat.emissiveTexture)] : white_;
        d.worldBounds = inst.worldBounds.empty() ? mesh.bounds.transformed(inst.transform) : inst.worldBounds;
        const glm::vec3 size = d.worldBounds.size();
        d.worldSize = std::max({size.x, size.y, size.z});
        d.uniforms.model = inst.transform;
        d.uniforms.normalMatrix = glm::mat4(glm::transpose(glm::inverse(glm::mat3(inst.transform))));
        d.uniforms.baseColor = mat.baseColor;
        d.uniforms.emissive = glm::vec4(mat.emissive, 0.0f);
        d.uniforms.material = glm::vec4(mat.metallic, mat.roughness, mat.normalTexture >= 0 ? 1.0f : 0.0f,
                                        mat.baseColorTexture >= 0 ? 1.0f : 0.0f);
        d.uniforms.maps = glm::vec4(mat.metallicRoughnessTexture >= 0 ? 1.0f : 0.0f,
                                    mat.emissiveTexture >= 0 ? 1.0f : 0.0f, 0.0f, 0.0f);
        hasMaterialMaps_ = hasMaterialMaps_ || d.hasMaterialMaps();
        draws_.push_back(d);
        triangles_ += mesh.indexCount / 3;
    }
    // One record per draw, read by the shaders at the draw's first instance: a frame pushes no
    // per-draw uniforms.
    std::vector<DrawUniforms> records;
    records.reserve(draws_.size());
    for (const GpuDraw& d : draws_)
        records.push_back(d.uniforms);
    drawRecords_ = device.createBuffer({std::max<size_t>(records.size(), 1) * sizeof(DrawUniforms),
                                        kBufferStorage | kBufferTransfer, MemoryAccess::GpuOnly,
                                        scene.name + " draw records", "scene.draws"},
                                       records.empty() ? nullptr : records.data());
    std::vector<uint32_t> drawIndices(std::max<size_t>(draws_.size(), 1));
    std::iota(drawIndices.begin(), drawIndices.end(), 0u);
    drawIndices_ = device.createBuffer({drawIndices.size() * sizeof(uint32_t), kBufferVertex,
                                        MemoryAccess::GpuOnly, scene.name + " draw indices", "scene.draws"},
                                       drawIndices.data());
    batchDraws();
}

void GpuScene::batchDraws() {
    // By texture set, in scene order within one.
    const auto textures = [this](uint32_t i) {
        const GpuDraw& d = draws_[i];
        return std::array{d.baseColor.bits, d.normal.bits, d.metallicRoughnessMap.bits, d.emissiveMap.bits};
    };
    batchedDraws_.resize(draws_.size());
    std::iota(batchedDraws_.begin(), batchedDraws_.end(), 0u);
    std::stable_sort(batchedDraws_.begin(), batchedDraws_.end(),
                     [&](uint32_t a, uint32_t b) { return textures(a) < textures(b); });
    for (uint32_t k = 0; k < batchedDraws_.size(); ++k) {
        if (k == 0 || textures(batchedDraws_[k]) != textures(batchedDraws_[k - 1]))
            batches_.push_back({k, 0});
        ++batches_.back().count;
    }
}

GpuScene::~GpuScene() {
    device_.waitIdle();
    for (rhi::TextureHandle t : textures_)
        device_.destroy(t);
    device_.destroy(white_);
    device_.destroy(flatNormal_);
    device_.destroy(sampler_);
    device_.destroy(vertices_);
    device_.destroy(indices_);
    device_.destroy(lights_);
    device_.destroy(drawRecords_);
    device_.destroy(drawIndices_);
}

} // namespace lpv::engine
