// The occlusion pass: surfels into the geometry volume, then face transmittance.
#include "gi/GeometryVolume.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace lpv::gi {

// gv_common.glsl's GeometryInject.
struct GeometryVolume::InjectUniforms {
    glm::vec4 gridOrigin;
    glm::vec4 lightDirection;
    glm::mat4 invViewProjection;
    glm::vec4 camera;
    glm::ivec4 grid;
    glm::vec4 whiteTexelFlux;
    glm::vec4 lightPosition;
    glm::vec4 lightAxis;
    glm::ivec4 albedoSums;
};

// gv_gaps.comp's Gaps.
struct GapsUniforms {
    glm::vec4 gridOrigin;
    glm::ivec4 grid;
    glm::mat4 viewProjection;
    glm::vec4 invDepthColumn;
};

namespace {

// The most surfels a GV cell's albedo sums take: a count in 16 bits that leaves units of at least
// 0x8000 an albedo of 1 (gv_albedo_sums.glsl).
constexpr uint32_t kMaxAlbedoSurfels = 0x7fff;

} // namespace

GeometryVolume::GeometryVolume(rhi::Device& device, uint32_t lpvSize, bool keepAlbedo, uint32_t faceSlots,
                               bool cameraAreas, bool scratchPerSlot)
    : device_(device), lpvSize_(lpvSize), layered_(device.caps().vertexShaderLayer),
      cameraAreas_(cameraAreas) {
    using namespace rhi;
    const uint32_t g = lpvSize + 1;
    // The light's coverage is rendered into (one layered draw, or one per slice), the camera's
    // marks, the albedo sums and the per-cell results written by compute; the tests read them all
    // back. Later passes sample what they do not read as images.
    const auto volume = [&](Format format, uint32_t size, uint32_t usage, const std::string& name) {
        return device.createTexture(
            {TextureKind::Tex3D, format, size, size, size, 1, usage | kTextureTransfer, name, "gi.gv"});
    };
    // 8 bits are enough: the faces use coverage up to 1 (a cell face fully covered), and additive
    // blending into a unorm target saturates there by itself. The camera's marks keep the same 8
    // bits per axis, packed (gv_packed_atomics.glsl).
    if (faceSlots == 0) throw std::invalid_argument("GeometryVolume: faceSlots must be at least 1");
    scratch_.resize(scratchPerSlot ? faceSlots : 1);
    for (Scratch& k : scratch_) {
        k.coverage = volume(Format::RGBA8Unorm, g, kTextureColorTarget | kTextureSampled, "gv coverage");
        k.cameraMarks = volume(Format::R32UI, g, kTextureStorage, "gv camera marks");
        if (cameraAreas)
            k.cameraAreas =
                device.createTexture({TextureKind::Tex3D, Format::R32UI, 3 * g, g, g, 1,
                                      kTextureStorage | kTextureTransfer, "gv camera areas", "gi.gv"});
    }
    for (uint32_t slot = 0; slot < faceSlots; ++slot)
        faces_.push_back(volume(Format::RGBA8Unorm, lpvSize, kTextureStorage | kTextureSampled,
                                slot == 0 ? std::string("gv face transmittance")
                                          : "gv face transmittance " + std::to_string(slot)));
    if (keepAlbedo) {
        albedoSums_ = device.createTexture({TextureKind::Tex3D, Format::R32UI, 2 * g, g, g, 1,
                                            kTextureStorage | kTextureTransfer, "gv albedo sums", "gi.gv"});
        albedo_ = volume(Format::RGBA8Unorm, lpvSize, kTextureStorage | kTextureSampled, "gv surfel albedo");
    }
    GraphicsPipelineDesc d;
    d.vertex = layered_ ? &shaders::gv_vpl_layered_vert : &shaders::gv_vpl_slice_vert;
    d.fragment = &shaders::gv_inject_frag;
    d.topology = PrimitiveTopology::PointList;
    d.colorFormats = {Format::RGBA8Unorm};
    d.blend = {BlendState::additive()};
    d.debugName = "gv inject light surfels";
    vplPipeline_ = device.createPipeline(d);
    d.vertex = layered_ ? &shaders::gv_vpl_point_layered_vert : &shaders::gv_vpl_point_slice_vert;
    d.debugName = "gv inject point light surfels";
    pointLightPipeline_ = device.createPipeline(d);
    cameraMarksPipeline_ =
        device.createPipeline(ComputePipelineDesc{&shaders::gv_camera_marks_comp, "gv camera marks"});
    gapsPipeline_ = device.createPipeline(ComputePipelineDesc{&shaders::gv_gaps_comp, "gv gaps"});
    facesPipeline_ = device.createPipeline(ComputePipelineDesc{&shaders::gv_faces_coverage_comp, "gv faces"});
    if (keepAlbedo) {
        const ShaderBinary* albedo[2][4] = {
            {&shaders::gv_albedo_count_camera_comp, &shaders::gv_albedo_count_vpls_comp,
             &shaders::gv_albedo_count_camera_vpls_comp, &shaders::gv_albedo_count_point_comp},
            {&shaders::gv_albedo_add_camera_comp, &shaders::gv_albedo_add_vpls_comp,
             &shaders::gv_albedo_add_camera_vpls_comp, &shaders::gv_albedo_add_point_comp}};
        for (int pass = 0; pass < 2; ++pass)
            for (int from = 0; from < 4; ++from)
                albedoPipelines_[pass][from] =
                    device.createPipeline(ComputePipelineDesc{albedo[pass][from], "gv albedo sums"});
        facesAlbedoPipeline_ =
            device.createPipeline(ComputePipelineDesc{&shaders::gv_faces_albedo_comp, "gv faces (albedo)"});
    }
    if (cameraAreas) {
        cameraAreasPipeline_ =
            device.createPipeline(ComputePipelineDesc{&shaders::gv_camera_areas_comp, "gv camera areas"});
        facesAreasPipeline_ = device.createPipeline(
            ComputePipelineDesc{&shaders::gv_faces_areas_coverage_comp, "gv faces (camera areas)"});
        if (keepAlbedo)
            facesAreasAlbedoPipeline_ = device.createPipeline(
                ComputePipelineDesc{&shaders::gv_faces_areas_albedo_comp, "gv faces (camera areas, albedo)"});
    }
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

GeometryVolume::~GeometryVolume() {
    device_.waitIdle();
    for (const Scratch& k : scratch_) {
        device_.destroy(k.coverage);
        device_.destroy(k.cameraMarks);
        if (k.cameraAreas) device_.destroy(k.cameraAreas);
    }
    for (rhi::TextureHandle t : faces_)
        device_.destroy(t);
    if (albedoSums_) {
        device_.destroy(albedoSums_);
        device_.destroy(albedo_);
        for (auto& pass : albedoPipelines_)
            for (rhi::ComputePipelineHandle p : pass)
                device_.destroy(p);
        device_.destroy(facesAlbedoPipeline_);
    }
    device_.destroy(vplPipeline_);
    device_.destroy(pointLightPipeline_);
    device_.destroy(cameraMarksPipeline_);
    device_.destroy(gapsPipeline_);
    device_.destroy(facesPipeline_);
    if (cameraAreas_) {
        device_.destroy(cameraAreasPipeline_);
        device_.destroy(facesAreasPipeline_);
        if (facesAreasAlbedoPipeline_) device_.destroy(facesAreasAlbedoPipeline_);
    }
    device_.destroy(pointSampler_);
}

uint32_t GeometryVolume::cameraSampleCount(uint32_t width, uint32_t height) {
    const uint32_t cols = kCameraSamplesPerRow;
    const uint32_t rows = std::max(1u, (cols * height + width / 2) / std::max(1u, width));
    return cols * rows;
}

void GeometryVolume::record(rhi::CommandList& cmd, const VolumeGrid& grid, const GeometrySources& src,
                            uint32_t slot) {
    const Build build{grid, &src, slot};
    recordTogether(cmd, std::span(&build, 1));
}

void GeometryVolume::recordTogether(rhi::CommandList& cmd, std::span<const Build> builds) {
    using namespace rhi;
    constexpr size_t kMaxBuilds = 4;
    if (builds.size() > kMaxBuilds)
        throw std::invalid_argument("GeometryVolume: more than 4 builds together");
    if (builds.size() > 1 && scratch_.size() == 1)
        throw std::invalid_argument("GeometryVolume: builds together need a volume made with scratchPerSlot");
    const uint32_t g = lpvSize_ + 1;
    std::array<Plan, kMaxBuilds> plans{};
    std::array<InjectUniforms, kMaxBuilds> uniforms{};
    for (size_t b = 0; b < builds.size(); ++b) {
        const GeometrySources& src = *builds[b].sources;
        Plan& p = plans[b];
        p.areas = src.depth && src.cameraAreas;
        if (p.areas && !cameraAreas_)
            throw std::invalid_argument("GeometryVolume: camera areas asked of a volume made without them");
        InjectUniforms& u = uniforms[b];
        u.gridOrigin = glm::vec4(builds[b].grid.origin, builds[b].grid.cellSize);
        u.lightDirection = glm::vec4(src.lightDirection, src.vplArea);
        u.invViewProjection = src.invViewProjection;
        u.camera = glm::vec4(src.cameraPosition, 0.0f);
        u.whiteTexelFlux = glm::vec4(src.whiteTexelFlux, 0.0f);
        u.grid = glm::ivec4(int(g), 0, int(src.vplCount), int(kCameraSamplesPerRow));
        if (src.depth) {
            const TextureDesc& d = device_.desc(src.depth);
            p.cameraSamples = cameraSampleCount(d.width, d.height);
        }
        p.marks = p.cameraSamples > 0 && !p.areas;
    }
    const auto slotOf = [&](size_t b) { return std::min(builds[b].slot, uint32_t(faces_.size()) - 1); };
    // Clears, and where a hole in a wall's coverage is a real gap, asked of the camera's depth once
    // per GV cell: each mark starts as its cell's gaps, in the top byte, with the marks' bytes clear
    // (gv_gaps.comp), which is the marks' clear.
    for (size_t b = 0; b < builds.size(); ++b) {
        const GeometrySources& src = *builds[b].sources;
        const Scratch& k = scratchOf(slotOf(b));
        if (plans[b].marks) {
            GapsUniforms gaps{};
            gaps.gridOrigin = uniforms[b].gridOrigin;
            gaps.grid = glm::ivec4(int(g), 0, 0, 0);
            gaps.viewProjection = src.viewProjection;
            gaps.invDepthColumn = src.invViewProjection[2];
            cmd.bindPipeline(gapsPipeline_);
            cmd.pushUniforms(0, &gaps, sizeof(gaps));
            cmd.bindTexture(1, src.depth, pointSampler_);
            cmd.bindStorageImage(3, k.cameraMarks);
            cmd.dispatch((g + 3) / 4, (g + 3) / 4, (g + 3) / 4);
        } else if (plans[b].areas) {
            cmd.clearTexture(k.cameraAreas, {0, 0, 0, 0});
        }
    }
    // A coarse cascade's samples add the areas they stand for (gv_camera_areas.comp); the finest
    // cascade's each mark up to kCameraPointsPerSample cells (gv_camera_marks.comp).
    for (size_t b = 0; b < builds.size(); ++b) {
        const Plan& p = plans[b];
        if (!p.areas && !p.marks) continue;
        const GeometrySources& src = *builds[b].sources;
        const Scratch& k = scratchOf(slotOf(b));
        cmd.bindPipeline(p.areas ? cameraAreasPipeline_ : cameraMarksPipeline_);
        cmd.pushUniforms(0, &uniforms[b], sizeof(InjectUniforms));
        cmd.bindTexture(1, src.depth, pointSampler_);
        cmd.bindTexture(2, src.normal, pointSampler_);
        cmd.bindStorageImage(3, p.areas ? k.cameraAreas : k.cameraMarks);
        cmd.dispatch((p.cameraSamples + 63) / 64);
        (p.areas ? areasSlot_ : marksSlot_) = slotOf(b);
    }
    // The camera's albedo in the finest cascade only, as its marks: a coarse cascade's is the
    // light's. One set of sums: one build may gather it.
    bool gathered = false;
    for (size_t b = 0; b < builds.size(); ++b) {
        const GeometrySources& src = *builds[b].sources;
        if (!albedoSums_ || !src.surfelAlbedo) continue;
        if (gathered) throw std::invalid_argument("GeometryVolume: two builds together gather albedo");
        gathered = true;
        plans[b].albedo = addAlbedoSums(cmd, uniforms[b], src, plans[b].marks ? plans[b].cameraSamples : 0);
        // Asked for with no surfel to give it: none anywhere.
        if (!plans[b].albedo) cmd.clearTexture(albedo_, {0, 0, 0, 0});
    }
    // The light's surfels, as the radiance injection: one layered draw per surfel set, or every set
    // once per slice.
    const uint32_t passes = layered_ ? 1 : g;
    for (size_t b = 0; b < builds.size(); ++b) {
        const GeometrySources& src = *builds[b].sources;
        InjectUniforms& u = uniforms[b];
        for (uint32_t slice = 0; slice < passes; ++slice) {
            RenderPassDesc pass;
            // Cleared as the pass begins (a slice's pass, its slice).
            pass.colors[0] = {scratchOf(slotOf(b)).coverage, 0, slice, LoadOp::Clear};
            pass.colors[0].layered = layered_;
            pass.colorCount = 1;
            pass.debugName = layered_ ? "gv inject" : "gv inject slice";
            cmd.beginRenderPass(pass);
            u.grid.y = int(slice);
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
            cmd.endRenderPass();
        }
    }
    for (size_t b = 0; b < builds.size(); ++b) {
        const Plan& p = plans[b];
        const Scratch& k = scratchOf(slotOf(b));
        // y: camera samples taken (only then is the camera's coverage closed over holes).
        const glm::ivec4 faceGrid(int(lpvSize_), p.cameraSamples > 0 ? 1 : 0, 0, 0);
        // Without albedo this build leaves albedo_ as it was (another cascade's, or none).
        cmd.bindPipeline(p.areas ? (p.albedo ? facesAreasAlbedoPipeline_ : facesAreasPipeline_)
                                 : (p.albedo ? facesAlbedoPipeline_ : facesPipeline_));
        cmd.pushUniforms(0, &faceGrid, sizeof(faceGrid));
        cmd.bindTexture(1, k.coverage, pointSampler_);
        cmd.bindStorageImage(2, faces_[slotOf(b)]);
        cmd.bindStorageImage(3, p.areas ? k.cameraAreas : k.cameraMarks);
        if (p.albedo) {
            cmd.bindStorageImage(4, albedoSums_);
            cmd.bindStorageImage(5, albedo_);
        }
        cmd.dispatch((lpvSize_ + 3) / 4, (lpvSize_ + 3) / 4, (lpvSize_ + 3) / 4);
    }
    if (!builds.empty()) lastSlot_ = slotOf(builds.size() - 1);
}

bool GeometryVolume::addAlbedoSums(rhi::CommandList& cmd, const InjectUniforms& base,
                                   const GeometrySources& src, uint32_t cameraSamples) {
    const uint32_t vpls = src.vpls ? src.vplCount : 0;
    uint32_t surfels = cameraSamples + vpls;
    for (const PointLightSurfels& light : src.pointLights)
        surfels += light.vpls ? light.count : 0;
    if (surfels == 0) return false;
    cmd.clearTexture(albedoSums_, {0, 0, 0, 0});
    // Where every surfel could land in one cell and count past kMaxAlbedoSurfels, take every
    // stride-th (the mean stays a mean).
    const uint32_t stride = (surfels + kMaxAlbedoSurfels - 1) / kMaxAlbedoSurfels;
    const auto groups = [&](uint32_t n) { return ((n + stride - 1) / stride + 63) / 64; };
    InjectUniforms u = base;
    u.grid.z = int(vpls);
    const int from = cameraSamples == 0 ? 1 : vpls == 0 ? 0 : 2;
    u.albedoSums = glm::ivec4(0, int(stride), int(cameraSamples), 0);
    for (int pass = 0; pass < 2; ++pass) {
        // Pass 0 counts each cell's surfels, pass 1 adds their albedo: every count is in before
        // the first albedo is added.
        if (cameraSamples + vpls > 0) {
            cmd.bindPipeline(albedoPipelines_[pass][from]);
            cmd.pushUniforms(0, &u, sizeof(u));
            if (vpls > 0) cmd.bindStorageBuffer(1, src.vpls);
            if (cameraSamples > 0) {
                cmd.bindTexture(2, src.depth, pointSampler_);
                cmd.bindTexture(3, src.normal, pointSampler_);
                cmd.bindTexture(5, src.albedo ? src.albedo : src.normal, pointSampler_);
            }
            cmd.bindStorageImage(4, albedoSums_);
            cmd.dispatch(groups(cameraSamples + vpls));
        }
        for (const PointLightSurfels& light : src.pointLights) {
            if (!light.vpls || light.count == 0) continue;
            InjectUniforms lu = u;
            lu.grid.z = int(light.count);
            lu.albedoSums.z = 0;
            // The cone's cosines (a point light's lets every direction through), the intensity
            // and 1 / range^2, as the RSM was lit (gv_common.glsl).
            lu.lightDirection = glm::vec4(light.light.intensityCos.w, light.light.spotCos.w, 0.0f, 0.0f);
            lu.whiteTexelFlux = glm::vec4(glm::vec3(light.light.intensityCos), 0.0f);
            lu.lightPosition = glm::vec4(light.position, light.vplSolidAngle);
            lu.lightAxis = glm::vec4(light.axis, light.light.positionInvRange2.w);
            cmd.bindPipeline(albedoPipelines_[pass][3]);
            cmd.pushUniforms(0, &lu, sizeof(lu));
            cmd.bindStorageBuffer(1, light.vpls);
            cmd.bindStorageImage(4, albedoSums_);
            cmd.dispatch(groups(light.count));
        }
    }
    return true;
}

} // namespace lpv::gi
