// The VPL gather pass: a fullscreen triangle per set of VPLs, added into one target.
#include "gi/VplGather.h"

#include "EngineShaders.h"
#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace lpv::gi {

// The shaders' count (gathered_cascades.glsl, read by gi/CMakeLists.txt), which also sizes the
// gathered lookup variants CMake builds.
static_assert(VplGather::kCascades == LPV_GATHERED_CASCADES, "gathered_cascades.glsl and kCascades differ");

namespace {

// std140 block `Gather` of vpl_gather.frag.
struct GatherUniforms {
    glm::mat4 invViewProjection;
    glm::vec4 gridOrigin[VplGather::kCascades];
    glm::ivec4 grid;
    glm::vec4 params;
    glm::ivec4 vpls;
    glm::ivec4 pixels;
    glm::uvec4 faces;
    glm::mat4 lightViewProjection;
    glm::ivec4 windows;
};

} // namespace

VplGather::VplGather(rhi::Device& device) : device_(device), windows_(device) {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &engine::shaders::fullscreen_vert;
    d.fragment = &shaders::vpl_gather_frag;
    d.colorFormats = {Format::RGBA16F};
    d.blend = {BlendState::additive()};
    d.debugName = "vpl gather";
    pipeline_ = device.createPipeline(d);
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    noFaceSlots_ = device.createTexture({TextureKind::Tex3D, Format::R32UI, 1, 1, 1, 1,
                                         kTextureSampled | kTextureTransfer, "vpl gather, no face slots",
                                         "render.lighting"});
    const uint32_t none = 0;
    device.uploadTexture(noFaceSlots_, 0, &none, sizeof(none));
    noFaces_ =
        device.createTexture({TextureKind::Tex3D, Format::R32UI, 1, 1, 1, 1,
                              kTextureStorage | kTextureTransfer, "vpl gather, no faces", "render.lighting"});
    device.uploadTexture(noFaces_, 0, &none, sizeof(none));
}

VplGather::~VplGather() {
    if (target_) device_.destroy(target_);
    device_.destroy(noFaceSlots_);
    device_.destroy(noFaces_);
    device_.destroy(pipeline_);
    device_.destroy(pointSampler_);
}

uint64_t VplGather::resize(uint32_t width, uint32_t height) {
    if (target_) {
        const rhi::TextureDesc& d = device_.desc(target_);
        if (d.width == width && d.height == height) return uint64_t(width) * height * 8;
        device_.destroy(target_);
    }
    rhi::TextureDesc d;
    d.width = width;
    d.height = height;
    d.format = rhi::Format::RGBA16F;
    d.usage = rhi::kTextureColorTarget | rhi::kTextureSampled;
    d.debugName = "vpl gather";
    // Screen-sized, as the lookup's targets, which the renderer counts (the GI's plan holds what
    // its settings alone size).
    d.category = "render.lighting";
    target_ = device_.createTexture(d);
    return uint64_t(width) * height * 8;
}

void VplGather::record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                       const engine::GBufferView& gbuffer, std::span<const VolumeGrid> cascades,
                       float blendBand, float intensity, uint32_t divisor,
                       std::span<const GatherSource> sources) {
    using namespace rhi;
    GatherUniforms u;
    u.invViewProjection = camera.invViewProjection;
    for (uint32_t c = 0; c < kCascades; ++c) {
        const VolumeGrid& g = cascades[std::min<size_t>(c, cascades.size() - 1)];
        u.gridOrigin[c] = glm::vec4(g.origin, g.cellSize);
    }
    u.grid = glm::ivec4(int(cascades[0].size), int(cascades.size()), 0, 0);
    u.pixels = glm::ivec4(int(divisor), int(gbuffer.width), int(gbuffer.height), 0);
    // The sun's windows where the boxes are now (the same the draws test against).
    const size_t last = std::min<size_t>(cascades.size(), kCascades) - 1;
    for (const GatherSource& s : sources) {
        if (!s.vpls || !s.windows || s.listed || s.cascade < 0) continue;
        const auto k = size_t(s.cascade);
        windows_.record(cmd, s.vpls, s.side, k < last ? std::optional(cascades[k]) : std::nullopt,
                        k > 0 ? std::optional(cascades[k - 1]) : std::nullopt, s.windows);
    }
    RenderPassDesc pass;
    pass.colors[0] = {target_, 0, 0, LoadOp::Clear};
    pass.colorCount = 1;
    pass.debugName = "vpl gather";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.bindTexture(2, gbuffer.depth, pointSampler_);
    cmd.bindTexture(3, gbuffer.normal, pointSampler_);
    for (const GatherSource& s : sources) {
        if (!s.vpls || (s.cascade < 0 && s.cascades == 0)) continue;
        u.grid.z = s.cascade;
        u.grid.w = int(s.cascades);
        const bool marched = bool(s.faces);
        u.params = glm::vec4(s.listed ? 1.0f : intensity, blendBand, s.nearest, marched ? 1.0f : 0.0f);
        u.vpls = glm::ivec4(int(s.slots), int(s.side), int(s.facesCascade), s.listed ? 1 : 0);
        u.faces = glm::uvec4(s.facesStamp, 0u, 0u, 0u);
        u.lightViewProjection = s.listed ? glm::mat4(0.0f) : s.lightViewProjection;
        const bool windowed = s.windows && !s.listed && s.cascade >= 0;
        u.windows = glm::ivec4(windowed ? 1 : 0, int(VplWindows::room(s.side)), 0, 0);
        cmd.pushUniforms(0, &u, sizeof(u));
        // The shader declares both views; the one it does not read is bound to the same buffer.
        cmd.bindStorageBuffer(1, s.vpls);
        cmd.bindStorageBuffer(5, s.vpls);
        cmd.bindStorageBuffer(7, windowed ? s.windows : s.vpls);
        cmd.bindTexture(6, s.listed ? s.faceSlots : noFaceSlots_, pointSampler_);
        cmd.bindStorageImage(4, marched ? s.faces : noFaces_);
        cmd.draw(3);
    }
    cmd.endRenderPass();
}

engine::WorkCounts gatherWork(uint64_t pixels, uint64_t slots, uint64_t draws, uint32_t marchedFaces) {
    engine::WorkCounts w;
    w.pixelsShaded = pixels * draws;
    w.texelsRead = pixels * draws * 2;
    w.texelsWritten = pixels * draws; // added: read and written
    // A texel reads a sixteenth of the slots (48 bytes each, mostly from cache: counted once per
    // texel's block of 16) and spends about 30 operations on each, and where marched about
    // `marchedFaces` point fetches and 10 operations a face.
    const uint64_t pairs = pixels * (slots / 16);
    w.bytesMoved = pixels * 16 + pairs * 48 / 16;
    w.aluOps = pairs * (30 + 10 * uint64_t(marchedFaces));
    w.texelsRead += pairs * marchedFaces;
    return w;
}

} // namespace lpv::gi
