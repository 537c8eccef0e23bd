// The occlusion pass: surfels into the geometry volume, then face transmittance.
#include "gi/GeometryVolume.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace lpv::gi {
namespace {

struct InjectUniforms {
    glm::vec4 gridOrigin;
    glm::vec4 lightDirection;
    glm::mat4 invViewProjection;
    glm::vec4 camera;
    glm::ivec4 grid;
    glm::vec4 whiteTexelFlux;
    glm::vec4 lightPosition;
    glm::vec4 lightAxis;
};

} // namespace

GeometryVolume::GeometryVolume(rhi::Device& device, uint32_t lpvSize, bool keepAlbedo, uint32_t faceSlots,
                               bool cameraAreas)
    : device_(device), lpvSize_(lpvSize), layered_(device.caps().vertexShaderLayer) {
    using namespace rhi;
    const uint32_t g = lpvSize + 1;
    // Coverage and albedo sums are rendered into (one layered draw, or one per slice), the per-cell results
    // are written by compute; all are sampled by later passes and read back by the tests.
    const auto volume = [&](Format format, uint32_t size, uint32_t writeUsage, const std::string& name) {
        return device.createTexture({TextureKind::Tex3D, format, size, size, size, 1,
                                     writeUsage | kTextureSampled | kTextureTransfer, name, "gi.gv"});
    };
    // 8 bits are enough: the faces use coverage up to 1 (a cell face fully covered), and additive
    // blending into a unorm target saturates there by itself.
    coverage_ = volume(Format::RGBA8Unorm, g, kTextureColorTarget, "gv coverage");
    cameraCoverage_ = volume(Format::RGBA8Unorm, g, kTextureColorTarget, "gv camera coverage");
    if (faceSlots == 0) throw std::invalid_argument("GeometryVolume: faceSlots must be at least 1");
    for (uint32_t slot = 0; slot < faceSlots; ++slot)
        faces_.push_back(volume(Format::RGBA8Unorm, lpvSize, kTextureStorage,
                                slot == 0 ? std::string("gv face transmittance")
                                          : "gv face transmittance " + std::to_string(slot)));
    if (keepAlbedo) {
        albedoSum_ = volume(Format::RGBA16F, g, kTextureColorTarget, "gv albedo sum");
        albedo_ = volume(Format::RGBA8Unorm, lpvSize, kTextureStorage, "gv surfel albedo");
    }
    GraphicsPipelineDesc d;
    d.vertex = layered_ ? &shaders::gv_vpl_layered_vert : &shaders::gv_vpl_slice_vert;
    d.fragment = keepAlbedo ? &shaders::gv_inject_albedo_frag : &shaders::gv_inject_coverage_frag;
    d.topology = PrimitiveTopology::PointList;
    BlendState max = BlendState::additive();
    max.colorOp = max.alphaOp = BlendOp::Max;
    d.colorFormats = {Format::RGBA8Unorm, Format::RGBA8Unorm};
    d.blend = {BlendState::additive(), max};
    if (keepAlbedo) {
        d.colorFormats.push_back(Format::RGBA16F);
        d.blend.push_back(BlendState::additive());
    }
    d.debugName = "gv inject light surfels";
    vplPipeline_ = device.createPipeline(d);
    d.vertex = layered_ ? &shaders::gv_vpl_point_layered_vert : &shaders::gv_vpl_point_slice_vert;
    d.debugName = "gv inject point light surfels";
    pointLightPipeline_ = device.createPipeline(d);
    const rhi::ShaderBinary* cameraLayered[3] = {&shaders::gv_camera0_layered_vert,
                                                 &shaders::gv_camera1_layered_vert,
                                                 &shaders::gv_camera2_layered_vert};
    const rhi::ShaderBinary* cameraSlice[3] = {
        &shaders::gv_camera0_slice_vert, &shaders::gv_camera1_slice_vert, &shaders::gv_camera2_slice_vert};
    d.debugName = "gv inject camera surfels";
    for (size_t kind = 0; kind < 3; ++kind) {
        d.vertex = layered_ ? cameraLayered[kind] : cameraSlice[kind];
        cameraPipelines_[kind] = device.createPipeline(d);
    }
    facesPipeline_ = device.createPipeline(ComputePipelineDesc{
        keepAlbedo ? &shaders::gv_faces_albedo_comp : &shaders::gv_faces_coverage_comp, "gv faces"});
    if (cameraAreas) {
        cameraAreas_ = device.createTexture({TextureKind::Tex3D, Format::R32UI, 3 * g, g, g, 1,
                                             kTextureStorage | kTextureSampled | kTextureTransfer,
                                             "gv camera areas", "gi.gv"});
        cameraAreasPipeline_ =
            device.createPipeline(ComputePipelineDesc{&shaders::gv_camera_areas_comp, "gv camera areas"});
        facesAreasPipeline_ = device.createPipeline(ComputePipelineDesc{
            keepAlbedo ? &shaders::gv_faces_areas_albedo_comp : &shaders::gv_faces_areas_coverage_comp,
            "gv faces (camera areas)"});
    }
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

GeometryVolume::~GeometryVolume() {
    device_.waitIdle();
    device_.destroy(coverage_);
    device_.destroy(cameraCoverage_);
    for (rhi::TextureHandle t : faces_)
        device_.destroy(t);
    if (albedoSum_) device_.destroy(albedoSum_);
    if (albedo_) device_.destroy(albedo_);
    device_.destroy(vplPipeline_);
    device_.destroy(pointLightPipeline_);
    for (rhi::GraphicsPipelineHandle p : cameraPipelines_)
        device_.destroy(p);
    device_.destroy(facesPipeline_);
    if (cameraAreas_) {
        device_.destroy(cameraAreas_);
        device_.destroy(cameraAreasPipeline_);
        device_.destroy(facesAreasPipeline_);
    }
    device_.destroy(pointSampler_);
}

uint32_t GeometryVolume::cameraSampleCount(uint32_t width, uint32_t height) const {
    const uint32_t cols = kCameraSamplesPerRow;
    const uint32_t rows = std::max(1u, (cols * height + width / 2) / std::max(1u, width));
    return cols * rows;
}

void GeometryVolume::build(rhi::CommandList& cmd, const VolumeGrid& grid, const GeometrySources& src,
                           uint32_t slot) {
    using namespace rhi;
    const bool areas = src.depth && src.cameraAreas;
    if (areas && !cameraAreas_)
        throw std::invalid_argument("GeometryVolume: camera areas asked of a volume made without them");
    lastSlot_ = std::min(slot, uint32_t(faces_.size()) - 1);
    cmd.clearTexture(coverage_, {0, 0, 0, 0});
    if (!areas) cmd.clearTexture(cameraCoverage_, {0, 0, 0, 0}); // with areas nothing reads it
    if (albedoSum_) cmd.clearTexture(albedoSum_, {0, 0, 0, 0});
    const uint32_t g = lpvSize_ + 1;
    InjectUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    u.lightDirection = glm::vec4(src.lightDirection, src.vplArea);
    u.invViewProjection = src.invViewProjection;
    u.camera = glm::vec4(src.cameraPosition, 0.0f);
    u.whiteTexelFlux = glm::vec4(src.whiteTexelFlux, 0.0f);
    uint32_t cameraSamples = 0;
    if (src.depth) {
        const TextureDesc& d = device_.desc(src.depth);
        cameraSamples = cameraSampleCount(d.width, d.height);
    }
    if (areas) {
        cmd.clearTexture(cameraAreas_, {0, 0, 0, 0});
        u.grid = glm::ivec4(int(g), 0, int(src.vplCount), int(kCameraSamplesPerRow));
        cmd.bindPipeline(cameraAreasPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindTexture(1, src.depth, pointSampler_);
        cmd.bindTexture(2, src.normal, pointSampler_);
        cmd.bindStorageImage(3, cameraAreas_);
        cmd.dispatch((cameraSamples + 63) / 64);
    }
    // As the radiance injection: one layered draw per surfel set, or every set once per slice.
    const uint32_t passes = layered_ ? 1 : g;
    for (uint32_t slice = 0; slice < passes; ++slice) {
        RenderPassDesc pass;
        pass.colors[0] = {coverage_, 0, slice, LoadOp::Load};
        pass.colors[1] = {cameraCoverage_, 0, slice, LoadOp::Load};
        pass.colors[2] = {albedoSum_, 0, slice, LoadOp::Load};
        pass.colorCount = albedoSum_ ? 3 : 2;
        for (uint32_t c = 0; c < pass.colorCount; ++c)
            pass.colors[c].layered = layered_;
        pass.debugName = layered_ ? "gv inject" : "gv inject slice";
        cmd.beginRenderPass(pass);
        u.grid = glm::ivec4(int(g), int(slice), int(src.vplCount), int(kCameraSamplesPerRow));
        if (src.vplCount > 0) {
            cmd.bindPipeline(vplPipeline_);
            cmd.pushUniforms(0, &u, sizeof(u));
            cmd.bindStorageBuffer(1, src.vpls);
            cmd.draw(src.vplCount);
        }
        for (const PointLightSurfels& light : src.pointLights) {
            if (light.count == 0) continue;
            InjectUniforms lu = u;
            lu.grid.z = int(light.count);
            lu.lightPosition = glm::vec4(light.position, light.vplSolidAngle);
            lu.lightAxis = glm::vec4(light.axis, 0.0f);
            cmd.bindPipeline(pointLightPipeline_);
            cmd.pushUniforms(0, &lu, sizeof(lu));
            cmd.bindStorageBuffer(1, light.vpls);
            cmd.draw(light.count);
        }
        // The samples, then their 2 half-way points, then their 4 footprint edges (gv_camera_body.glsl).
        constexpr uint32_t kPointsOfKind[3] = {1, 2, 4};
        static_assert(kPointsOfKind[0] + kPointsOfKind[1] + kPointsOfKind[2] == kCameraPointsPerSample);
        for (size_t kind = 0; kind < 3 && cameraSamples > 0 && !areas; ++kind) {
            cmd.bindPipeline(cameraPipelines_[kind]);
            cmd.pushUniforms(0, &u, sizeof(u));
            cmd.bindTexture(1, src.depth, pointSampler_);
            cmd.bindTexture(2, src.normal, pointSampler_);
            cmd.bindTexture(3, src.albedo ? src.albedo : src.normal, pointSampler_);
            cmd.draw(cameraSamples * kPointsOfKind[kind]);
        }
        cmd.endRenderPass();
    }
    // y: camera surfels drawn (only then is the camera's coverage closed over holes).
    const glm::ivec4 faceGrid(int(lpvSize_), cameraSamples > 0 ? 1 : 0, 0, 0);
    cmd.bindPipeline(areas ? facesAreasPipeline_ : facesPipeline_);
    cmd.pushUniforms(0, &faceGrid, sizeof(faceGrid));
    cmd.bindTexture(1, coverage_, pointSampler_);
    cmd.bindStorageImage(2, faces_[lastSlot_]);
    if (areas)
        cmd.bindStorageImage(3, cameraAreas_);
    else
        cmd.bindTexture(3, cameraCoverage_, pointSampler_);
    if (albedo_) {
        cmd.bindTexture(4, albedoSum_, pointSampler_);
        cmd.bindStorageImage(5, albedo_);
    }
    cmd.dispatch((lpvSize_ + 3) / 4, (lpvSize_ + 3) / 4, (lpvSize_ + 3) / 4);
}

} // namespace lpv::gi
