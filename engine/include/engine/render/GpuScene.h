// A scene's GPU copy: vertex and index buffers (with each mesh's coarser levels of detail after
// the scene's own indices), material textures with CPU-built mip chains, the punctual-light buffer
// and the per-draw records (transform and material). Made once when a scene is set; a frame only
// binds what is here, so a frame's uniform ring holds per-pass constants only, whatever the number
// of draws (a 20,000-draw level overflowed it when each draw pushed its own).
#pragma once

#include "engine/scene/MeshLods.h"
#include "engine/scene/Scene.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>

#include <array>
#include <vector>

namespace lpv::engine {

// std430 element `DrawRecord` of engine/shaders/draw_uniforms.glsl: one per draw, in
// GpuScene::drawRecords() at the draw's index.
struct DrawUniforms {
    glm::mat4 model;
    glm::mat4 normalMatrix;
    glm::vec4 baseColor;
    glm::vec4 emissive;
    glm::vec4 material; // metallic, roughness, has normal map, has base color texture
    glm::vec4 maps;     // x: has a metallic-roughness texture, y: has an emissive texture
};
static_assert(sizeof(DrawUniforms) == 192, "DrawUniforms must match the std430 struct DrawRecord");

// std430 element of `Lights` in lighting.frag.
struct GpuPunctualLight {
    glm::vec4 positionRange;
    glm::vec4 colorIntensity;
    glm::vec4 directionType;
    glm::vec4 cone;
};

// An index range of one level of detail and how far (m, in the world) it strays from the mesh.
struct DrawLod {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    float worldError = 0.0f;
};

struct GpuDraw {
    // This draw's record in GpuScene::drawRecords(): what a draw passes as its first instance
    // (the shaders read the record at gl_InstanceIndex).
    uint32_t index = 0;
    // lods[0] is the full mesh; each further level is coarser (MeshLods.h).
    std::array<DrawLod, kMaxMeshLods> lods{};
    uint32_t lodCount = 1;
    rhi::TextureHandle baseColor; // a 1x1 white texture when the material has none
    rhi::TextureHandle normal;    // a 1x1 flat normal when the material has none
    // Read only by the G-buffer's and RSMs' map variants, where uniforms.maps says the material has one;
    // a 1x1 white texture otherwise.
    rhi::TextureHandle metallicRoughnessMap, emissiveMap;
    float worldSize = 0.0f; // largest side of the world bounds (m): size filters use it
    Bounds worldBounds;     // culling against a view (Bounds::outsideClipVolume)
    DrawUniforms uniforms;  // the CPU copy of the record

    // A metallic-roughness or emissive map: drawn by the G-buffer's variant that reads them.
    bool hasMaterialMaps() const { return uniforms.maps.x > 0.5f || uniforms.maps.y > 0.5f; }
    // The coarsest level that strays at most `maxError` m from the mesh (the full mesh when none).
    const DrawLod& lodWithin(float maxError) const {
        uint32_t k = 0;
        while (k + 1 < lodCount && lods[k + 1].worldError <= maxError)
            ++k;
        return lods[k];
    }
};

// A run of GpuScene::batchedDraws() whose draws bind the same textures (one material's, mostly):
// a pass binds them once and draws the run as one indirect multi-draw (MultiDraw).
struct DrawBatch {
    uint32_t first = 0; // into batchedDraws()
    uint32_t count = 0;
};

// Where a multi-drawn vertex shader reads its draw's index (GpuScene::drawIndices(), a per-instance
// stream at vertex buffer slot 1): draw_uniforms.glsl's DRAW_INDEX_ATTRIBUTE.
inline constexpr uint32_t kDrawIndexAttribute = 6;
inline constexpr uint32_t kDrawIndexSlot = 1;

class GpuScene {
public:
    static constexpr uint32_t kMaxPunctualLights = 1024;

    GpuScene(rhi::Device& device, const Scene& scene);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    rhi::BufferHandle vertices() const { return vertices_; }
    rhi::BufferHandle indices() const { return indices_; }
    rhi::BufferHandle lights() const { return lights_; }
    uint32_t lightCount() const { return lightCount_; }
    // The records in lights(), in the order of the scene's point and spot lights.
    const std::vector<GpuPunctualLight>& lightRecords() const { return lightRecords_; }
    const std::vector<GpuDraw>& draws() const { return draws_; }
    // Every draw's DrawUniforms, at GpuDraw::index: bound as a storage buffer at binding 1
    // (draw_uniforms.glsl) by every pass that draws the scene. Memory category "scene.draws".
    rhi::BufferHandle drawRecords() const { return drawRecords_; }
    // 0, 1, ... one uint per draw: bound as a per-instance vertex stream, it gives each draw of a
    // multi-draw its first instance, the index of its record (CommandList::drawIndexedIndirect).
    rhi::BufferHandle drawIndices() const { return drawIndices_; }
    // The draws' indices ordered so that those binding the same textures are together, and the runs.
    const std::vector<uint32_t>& batchedDraws() const { return batchedDraws_; }
    const std::vector<DrawBatch>& batches() const { return batches_; }
    // Whether any draw hasMaterialMaps().
    bool hasMaterialMaps() const { return hasMaterialMaps_; }
    rhi::SamplerHandle materialSampler() const { return sampler_; }
    uint64_t triangleCount() const { return triangles_; }

private:
    void batchDraws();

    rhi::Device& device_;
    rhi::BufferHandle vertices_, indices_, lights_, drawRecords_, drawIndices_;
    std::vector<rhi::TextureHandle> textures_;
    rhi::TextureHandle white_, flatNormal_;
    bool hasMaterialMaps_ = false;
    rhi::SamplerHandle sampler_;
    std::vector<GpuDraw> draws_;
    std::vector<uint32_t> batchedDraws_;
    std::vector<DrawBatch> batches_;
    std::vector<GpuPunctualLight> lightRecords_;
    uint32_t lightCount_ = 0;
    uint64_t triangles_ = 0;
};

} // namespace lpv::engine
