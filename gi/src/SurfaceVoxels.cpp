// The scene drawn along each axis onto a cascade's cell faces (surface_voxels.vert/.frag).
#include "gi/SurfaceVoxels.h"

#include "GiShaders.h"
#include "engine/render/GpuScene.h"

#include <glm/vec4.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace lpv::gi {
namespace {

// std140 block `Voxelize` of surface_voxels.vert/.frag.
struct VoxelizeUniforms {
    glm::vec4 gridOrigin; // xyz: corner of cell 0, w: cell size
    glm::uvec4 grid;      // x: cells a side, y: the stamp, z: pixels a column's side
};

constexpr uint32_t kAxisShift = 30; // a draw index's axis bits (surface_voxels.vert)

} // namespace

SurfaceVoxels::SurfaceVoxels(rhi::Device& device, uint32_t gridSize, uint32_t stampLimit)
    : device_(device), gridSize_(gridSize), multiDraw_(device, "surface voxels", "render.draw_commands"),
      stampLimit_(stampLimit) {
    if (stampLimit < 2 || stampLimit > kStampLimit)
        throw std::invalid_argument("SurfaceVoxels: stamp limit out of range");
    using namespace rhi;
    // Stamp 0 is no pass's: every face starts open.
    const std::vector<uint32_t> zeros(size_t(3) * gridSize * gridSize * gridSize, 0u);
    for (uint32_t c = 0; c < kCascades; ++c) {
        const std::string name = "surface faces, cascade " + std::to_string(c);
        faces_[c] = device.createTexture({TextureKind::Tex3D, Format::R32UI, 3 * gridSize, gridSize, gridSize,
                                          1, kTextureStorage | kTextureTransfer, name, "gi.lpv"});
        device.uploadTexture(faces_[c], 0, zeros.data(), zeros.size() * sizeof(uint32_t));
        areas_[c] = device.createTexture({TextureKind::Tex3D, Format::R32UI, 3 * gridSize, gridSize, gridSize,
                                          1, kTextureStorage | kTextureSampled | kTextureTransfer,
                                          "surface areas, cascade " + std::to_string(c), "gi.lpv"});
        device.uploadTexture(areas_[c], 0, zeros.data(), zeros.size() * sizeof(uint32_t));
        const uint32_t side = kSamplesPerSide * gridSize;
        targets_[c] = device.createTexture({TextureKind::Tex2D, Format::RGBA8Unorm, side, side, 1, 1,
                                            kTextureColorTarget, name + " target", "gi.lpv"});
    }
    GraphicsPipelineDesc d;
    d.vertex = &shaders::surface_voxels_vert;
    d.fragment = &shaders::surface_voxels_frag;
    d.vertexBuffers = {{sizeof(engine::Vertex)}};
    d.attributes = {{0, VertexFormat::Float3, offsetof(engine::Vertex, position)}};
    engine::addDrawIndexStream(d);
    d.colorFormats = {Format::RGBA8Unorm};
    d.debugName = "surface voxels";
    pipeline_ = device.createPipeline(d);
}

SurfaceVoxels::~SurfaceVoxels() {
    device_.waitIdle();
    for (uint32_t c = 0; c < kCascades; ++c) {
        device_.destroy(faces_[c]);
        device_.destroy(areas_[c]);
        device_.destroy(targets_[c]);
    }
    if (axisDraws_) device_.destroy(axisDraws_);
    device_.destroy(pipeline_);
}

uint64_t SurfaceVoxels::bytes(uint32_t gridSize) {
    const uint64_t side = uint64_t(kSamplesPerSide) * gridSize;
    return kCascades * (2 * uint64_t(3) * gridSize * gridSize * gridSize * 4 + side * side * 4);
}

uint64_t SurfaceVoxels::record(rhi::CommandList& cmd, const engine::GpuScene& scene, const VolumeGrid& grid,
                               uint32_t cascade) {
    using namespace rhi;
    if (cascade >= kCascades || grid.size != gridSize_)
        throw std::logic_error("SurfaceVoxels::record: cascade or grid size out of range");
    const uint32_t draws = uint32_t(scene.draws().size());
    if (draws >= (1u << kAxisShift)) throw std::length_error("SurfaceVoxels: over 2^30 draws");
    if (draws != axisDrawsFor_ && draws > 0) {
        if (axisDraws_) {
            device_.waitIdle();
            device_.destroy(axisDraws_);
        }
        std::vector<uint32_t> stream(size_t(3) * draws);
        for (uint32_t a = 0; a < 3; ++a)
            for (uint32_t k = 0; k < draws; ++k)
                stream[size_t(a) * draws + k] = k | (a << kAxisShift);
        axisDraws_ =
            device_.createBuffer({stream.size() * sizeof(uint32_t), kBufferVertex, MemoryAccess::GpuOnly,
                                  "surface voxels' draw axes", "render.draw_commands"},
                                 stream.data());
        axisDrawsFor_ = draws;
    }
    // 0 stays no pass's; the areas keep the stamp above their count.
    if (lastStamp_ + 1u >= stampLimit_) {
        for (uint32_t c = 0; c < kCascades; ++c) {
            cmd.clearTexture(faces_[c], {0, 0, 0, 0});
            cmd.clearTexture(areas_[c], {0, 0, 0, 0});
            stamps_[c] = 0;
        }
        lastStamp_ = 0;
    }
    ++lastStamp_;
    stamps_[cascade] = lastStamp_;
    engine::Bounds box;
    box.add(grid.origin);
    box.add(grid.origin + grid.cellSize * float(grid.size));
    RenderPassDesc pass;
    pass.colors[0] = {targets_[cascade], 0, 0, LoadOp::DontCare};
    pass.colorCount = 1;
    pass.debugName = "surface voxels";
    cmd.beginRenderPass(pass);
    uint64_t triangles = 0;
    if (draws > 0) {
        cmd.bindPipeline(pipeline_);
        const VoxelizeUniforms u{glm::vec4(grid.origin, grid.cellSize),
                                 glm::uvec4(grid.size, lastStamp_, kSamplesPerSide, 0u)};
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindVertexBuffer(0, scene.vertices());
        cmd.bindVertexBuffer(engine::kDrawIndexSlot, axisDraws_);
        cmd.bindIndexBuffer(scene.indices(), IndexType::Uint32);
        cmd.bindStorageBuffer(1, scene.drawRecords());
        cmd.bindStorageImage(2, faces_[cascade]);
        cmd.bindStorageImage(3, areas_[cascade]);
        multiDraw_.reserve(3 * draws);
        // Each draw that reaches the grid is culled and its level chosen once, drawn along each axis.
        for (const engine::GpuDraw& d : scene.draws()) {
            const engine::Bounds& b = d.worldBounds;
            if (b.empty() || glm::any(glm::lessThan(b.max, box.min)) ||
                glm::any(glm::greaterThan(b.min, box.max)))
                continue;
            // A surface within a quarter cell of the mesh marks the same faces.
            const engine::DrawLod& lod = d.lodWithin(0.25f * grid.cellSize);
            for (uint32_t axis = 0; axis < 3; ++axis)
                multiDraw_.add(lod, axis * draws + d.index);
            triangles += 3 * (lod.indexCount / 3);
        }
        if (triangles > 0) multiDraw_.draw(cmd);
    }
    cmd.endRenderPass();
    return triangles;
}

} // namespace lpv::gi
