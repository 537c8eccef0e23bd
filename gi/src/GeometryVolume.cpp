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
    // The light's coverage and the albedo sums are rendered into (one layered draw, or one per
    // slice), the camera's marks and the per-cell results written by compute; the tests read them
    // all back. Later passes sample what they do not read as images.
    const auto volume = [&](Format format, uint32_t size, uint32_t usage, const std::string& name) {
        return device.createTexture(
            {TextureKind::Tex3D, format, size, size, size, 1, usage | kTextureTransfer, name, "gi.gv"});
    };
    // 8 bits are enough: the faces use coverage up to 1 (a cell face fully covered), and additive
    // blending into a unorm target saturates there by itself. The camera's marks keep the same 8
    // bits per axis, packed (gv_packed_atomics.glsl).
    coverage_ = volume(Format::RGBA8Unorm, g, kTextureColorTarget | kTextureSampled, "gv coverage");
    cameraMarks_ = volume(Format::R32UI, g, kTextureStorage, "gv camera marks");
    if (faceSlots == 0) throw std::invalid_argument("GeometryVolume: faceSlots must be at least 1");
    for (uint32_t slot = 0; slot < faceSlots; ++slot)
        faces_.push_back(volume(Format::RGBA8Unorm, lpvSize, kTextureStorage | kTextureSampled,
                                slot == 0 ? std::string("gv face transmittance")
                                          : "gv face transmittance " + std::to_string(slot)));
    if (keepAlbedo) {
        albedoSum_ = volume(Format::RGBA16F, g, kTextureColorTarget | kTextureSampled, "gv albedo sum");
        albedo_ = volume(Format::RGBA8Unorm, lpvSize, kTextureStorage | kTextureSampled, "gv surfel albedo");
    }
    GraphicsPipelineDesc d;
    d.vertex = layered_ ? &shaders::gv_vpl_layered_vert : &shaders::gv_vpl_slice_vert;
    d.fragment = keepAlbedo ? &shaders::gv_inject_albedo_frag : &shaders::gv_inject_coverage_frag;
    d.topology = PrimitiveTopology::PointList;
    d.colorFormats = {Format::RGBA8Unorm};
    d.blend = {BlendState::additive()};
    if (keepAlbedo) {
        d.colorFormats.push_back(Format::RGBA16F);
        d.blend.push_back(BlendState::additive());
    }
    d.debugName = "gv inject light surfels";
    vplPipeline_ = device.createPipeline(d);
    d.vertex = layered_ ? &shaders::gv_vpl_point_layered_vert : &shaders::gv_vpl_point_slice_vert;
    d.debugName = "gv inject point light surfels";
    pointLightPipeline_ = device.createPipeline(d);
    if (keepAlbedo) {
        d.vertex = layered_ ? &shaders::gv_camera_albedo_layered_vert : &shaders::gv_camera_albedo_slice_vert;
        d.debugName = "gv inject camera albedo";
        cameraAlbedoPipeline_ = device.createPipeline(d);
    }
    cameraMarksPipeline_ =
        device.createPipeline(ComputePipelineDesc{&shaders::gv_camera_marks_comp, "gv camera marks"});
    facesPipeline_ = device.createPipeline(ComputePipelineDesc{
        keepAlbedo ? &shaders::gv_faces_albedo_comp : &shaders::gv_faces_coverage_comp, "gv faces"});
    if (cameraAreas) {
        cameraAreas_ = device.createTexture({TextureKind::Tex3D, Format::R32UI, 3 * g, g, g, 1,
                                             kTextureStorage | kTextureTransfer, "gv camera areas", "gi.gv"});
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
    device_.destroy(cameraMarks_);
    for (rhi::TextureHandle t : faces_)
        device_.destroy(t);
    if (albedoSum_) device_.destroy(albedoSum_);
    if (albedo_) device_.destroy(albedo_);
    device_.destroy(vplPipeline_);
    device_.destroy(pointLightPipeline_);
    if (cameraAlbedoPipeline_) device_.destroy(cameraAlbedoPipeline_);
    device_.destroy(cameraMarksPipeline_);
    device_.destroy(facesPipeline_);
    if (cameraAreas_) {
        device_.destroy(cameraAreas_);
        device_.destroy(cameraAreasPipeline_);
        device_.destroy(facesAreasPipeline_);
    }
    device_.destroy(pointSampler_);
}

uint32_t GeometryVolume::cameraSampleCount(uint32_t width, uint32_t height) {
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
    const bool marks = cameraSamples > 0 && !areas;
    if (marks) {
        // The finest cascade's: every sample marks up to kCameraPointsPerSample cells.
        cmd.clearTexture(cameraMarks_, {0, 0, 0, 0});
        u.grid = glm::ivec4(int(g), 0, int(src.vplCount), int(kCameraSamplesPerRow));
        cmd.bindPipeline(cameraMarksPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindTexture(1, src.depth, pointSampler_);
        cmd.bindTexture(2, src.normal, pointSampler_);
        cmd.bindStorageImage(3, cameraMarks_);
        cmd.dispatch((cameraSamples + 63) / 64);
    }
    // The light's surfels and the samples' albedo, as the radiance injection: one layered draw per
    // surfel set, or every set once per slice.
    const uint32_t passes = layered_ ? 1 : g;
    for (uint32_t slice = 0; slice < passes; ++slice) {
        RenderPassDesc pass;
        pass.colors[0] = {coverage_, 0, slice, LoadOp::Load};
        pass.colors[1] = {albedoSum_, 0, slice, LoadOp::Load};
        pass.colorCount = albedoSum_ ? 2 : 1;
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
        if (marks && cameraAlbedoPipeline_) {
            cmd.bindPipeline(cameraAlbedoPipeline_);
            cmd.pushUniforms(0, &u, sizeof(u));
            cmd.bindTexture(1, src.depth, pointSampler_);
            cmd.bindTexture(2, src.normal, pointSampler_);
            cmd.bindTexture(3, src.albedo ? src.albedo : src.normal, pointSampler_);
            cmd.draw(cameraSamples);
        }
        cmd.endRenderPass();
    }
    // y: camera samples taken (only then is the camera's coverage closed over holes).
    const glm::ivec4 faceGrid(int(lpvSize_), cameraSamples > 0 ? 1 : 0, 0, 0);
    cmd.bindPipeline(areas ? facesAreasPipeline_ : facesPipeline_);
    cmd.pushUniforms(0, &faceGrid, sizeof(faceGrid));
    cmd.bindTexture(1, coverage_, pointSampler_);
    cmd.bindStorageImage(2, faces_[lastSlot_]);
    cmd.bindStorageImage(3, areas ? cameraAreas_ : cameraMarks_);
    if (albedo_) {
        cmd.bindTexture(4, albedoSum_, pointSampler_);
        cmd.bindStorageImage(5, albedo_);
    }
    cmd.dispatch((lpvSize_ + 3) / 4, (lpvSize_ + 3) / 4, (lpvSize_ + 3) / 4);
}

} // namespace lpv::gi
