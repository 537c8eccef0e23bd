// RSM fits (sun and spot) and pass.
#include "gi/ReflectiveShadowMap.h"

#include "GiShaders.h"
#include "rhi/Error.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::gi {
namespace {
struct RsmUniforms {
    glm::mat4 lightViewProjection;
    glm::vec4 lightDirection;
    glm::vec4 fluxScale;
};

// std140 block `SpotRsm` of rsm_spot.vert/.frag.
struct SpotRsmUniforms {
    glm::mat4 lightViewProjection;
    glm::vec4 lightPosition;
    glm::vec4 spotDirection;
    glm::vec4 cone;
    glm::vec4 intensity;
};

glm::vec3 spotAxis(const engine::Light& spot) {
    const float length = glm::length(spot.direction);
    return length > 0.0f ? spot.direction / length : glm::vec3(0.0f, -1.0f, 0.0f);
}

// A square perspective frustum from `light` along `axis` with sides at tanHalfAngle.
SpotRsmFit fitPerspective(const engine::Light& light, glm::vec3 axis, float tanHalfAngle, float reach) {
    SpotRsmFit f;
    const glm::vec3 up = std::fabs(axis.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    f.axis = axis;
    f.tanHalfAngle = tanHalfAngle;
    f.farPlane = std::max(light.range > 0.0f ? std::min(light.range, reach) : reach, 0.1f);
    // Depth precision follows far / near; 1/500 keeps D32F's reconstructed positions within
    // a millimetre at 10 m.
    f.nearPlane = std::max(0.02f, f.farPlane / 500.0f);
    const glm::mat4 view = glm::lookAt(light.position, light.position + axis, up);
    const glm::mat4 projection =
        glm::perspectiveRH_ZO(2.0f * std::atan(f.tanHalfAngle), 1.0f, f.nearPlane, f.farPlane);
    f.viewProjection = projection * view;
    return f;
}
} // namespace

SpotRsmFit fitSpotRsm(const engine::Light& spot, float reach) {
    // 1% wider than the cone, so its rim lands inside the outermost texels, not on the edge.
    const float halfAngle = std::clamp(spot.outerConeAngle, 0.01f, kMaxSpotRsmHalfAngle);
    return fitPerspective(spot, spotAxis(spot), std::tan(halfAngle) * 1.01f, reach);
}

glm::vec3 cubeFaceAxis(uint32_t face) {
    glm::vec3 axis(0.0f);
    axis[int(face / 2) % 3] = face % 2 == 0 ? 1.0f : -1.0f;
    return axis;
}

SpotRsmFit fitCubeFace(const engine::Light& point, uint32_t face, float reach) {
    return fitPerspective(point, cubeFaceAxis(face), 1.0f, reach);
}

ReflectiveShadowMap::ReflectiveShadowMap(rhi::Device& device, uint32_t size, RsmLight light)
    : device_(device), size_(size), light_(light),
      multiDraw_(device, light == RsmLight::Spot ? "spot rsm" : "rsm", "render.draw_commands") {
    using namespace rhi;
    depth_ = device.createTexture({TextureKind::Tex2D, Format::D32F, size, size, 1, 1,
                                   kTextureDepthTarget | kTextureSampled | kTextureTransfer, "rsm depth",
                                   "gi.rsm"});
    normal_ = device.createTexture({TextureKind::Tex2D, Format::RGBA16F, size, size, 1, 1,
                                    kTextureColorTarget | kTextureSampled | kTextureTransfer, "rsm normal",
                                    "gi.rsm"});
    flux_ = device.createTexture({TextureKind::Tex2D, Format::RGBA16F, size, size, 1, 1,
                                  kTextureColorTarget | kTextureSampled | kTextureTransfer, "rsm flux",
                                  "gi.rsm"});
    GraphicsPipelineDesc d;
    d.vertex = light == RsmLight::Spot ? &shaders::rsm_spot_vert : &shaders::rsm_vert;
    d.fragment = light == RsmLight::Spot ? &shaders::rsm_spot_frag : &shaders::rsm_frag;
    d.vertexBuffers = {{sizeof(engine::Vertex)}};
    d.attributes = {{0, VertexFormat::Float3, offsetof(engine::Vertex, position)},
                    {1, VertexFormat::Float3, offsetof(engine::Vertex, normal)},
                    {2, VertexFormat::Float2, offsetof(engine::Vertex, uv)}};
    engine::addDrawIndexStream(d);
    d.depthTest = d.depthWrite = true;
    d.depthCompare = CompareOp::Less;
    d.colorFormats = {Format::RGBA16F, Format::RGBA16F};
    d.depthFormat = Format::D32F;
    d.debugName = light == RsmLight::Spot ? "spot rsm" : "rsm";
    pipeline_ = device.createPipeline(d);
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linear.debugName = "rsm specular albedo";
    linearSampler_ = device.createSampler(linear);
}

ReflectiveShadowMap::~ReflectiveShadowMap() {
    device_.waitIdle();
    device_.destroy(depth_);
    device_.destroy(normal_);
    device_.destroy(flux_);
    device_.destroy(pipeline_);
    device_.destroy(linearSampler_);
}

glm::mat4 ReflectiveShadowMap::fit(const VolumeGrid& grid, glm::vec3 lightDirection) {
    const float extent = grid.cellSize * float(grid.size);
    const glm::vec3 center = grid.origin + glm::vec3(0.5f * extent);
    const float radius = 0.5f * std::sqrt(3.0f) * extent; // the volume's bounding sphere
    const glm::vec3 dir = glm::normalize(lightDirection);
    const glm::vec3 up = std::fabs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    // A light view through the world origin, so its orientation does not depend on the volume;
    // the volume's centre in that view is then snapped to whole texels.
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), dir, up);
    const float texel = 2.0f * radius / float(size_);
    glm::vec3 c = glm::vec3(view * glm::vec4(center, 1.0f));
    c.x = std::floor(c.x / texel) * texel;
    c.y = std::floor(c.y / texel) * texel;
    // Depth range: the bounding sphere, plus room behind it toward the light for occluders.
    const glm::mat4 projection = glm::orthoRH_ZO(c.x - radius, c.x + radius, c.y - radius, c.y + radius,
                                                 -c.z - 4.0f * radius, -c.z + radius);
    viewProjection_ = projection * view;
    texelArea_ = texel * texel;
    texelSide_ = texel;
    return viewProjection_;
}

uint64_t ReflectiveShadowMap::record(rhi::CommandList& cmd, const engine::GpuScene& scene,
                                     rhi::TextureHandle specularAlbedo, glm::vec3 lightDirection,
                                     glm::vec3 sunIrradiance, float minObjectSize, float lodTexels) {
    if (light_ != RsmLight::Sun) throw rhi::Error("ReflectiveShadowMap::record() on a spot light's RSM");
    RsmUniforms u;
    u.lightViewProjection = viewProjection_;
    u.lightDirection = glm::vec4(glm::normalize(lightDirection), 0.0f);
    u.fluxScale = glm::vec4(sunIrradiance * texelArea_, 0.0f);
    // An orthographic texel is the same size everywhere in the view.
    const float maxError = lodTexels * texelSide_;
    return draw(cmd, scene, specularAlbedo, &u, sizeof(u), minObjectSize,
                [maxError](const engine::GpuDraw&) { return maxError; });
}

uint64_t ReflectiveShadowMap::recordSpot(rhi::CommandList& cmd, const engine::GpuScene& scene,
                                         rhi::TextureHandle specularAlbedo, const engine::Light& spot,
                                         float reach, float lodTexels) {
    if (light_ != RsmLight::Spot) throw rhi::Error("ReflectiveShadowMap::recordSpot() on the sun's RSM");
    // As the analytic lights (gi/AnalyticLight.cpp): smoothstep needs edge0 < edge1.
    const float cosOuter = std::cos(spot.outerConeAngle);
    return recordPerspective(cmd, scene, specularAlbedo, spot, spotAxis(spot), fitSpotRsm(spot, reach),
                             cosOuter, std::max(std::cos(spot.innerConeAngle), cosOuter + 1e-4f), lodTexels);
}

uint64_t ReflectiveShadowMap::recordCubeFace(rhi::CommandList& cmd, const engine::GpuScene& scene,
                                             rhi::TextureHandle specularAlbedo, const engine::Light& point,
                                             uint32_t face, float reach, float lodTexels) {
    if (light_ != RsmLight::Spot) throw rhi::Error("ReflectiveShadowMap::recordCubeFace() on the sun's RSM");
    // No cone: every direction of the face gets the light's intensity (smoothstep from -1 is 1
    // over the whole face, whose directions are within 55 degrees of its axis).
    return recordPerspective(cmd, scene, specularAlbedo, point, cubeFaceAxis(face),
                             fitCubeFace(point, face, reach), -1.0f, -1.0f + 1e-4f, lodTexels);
}

uint64_t ReflectiveShadowMap::recordPerspective(rhi::CommandList& cmd, const engine::GpuScene& scene,
                                                rhi::TextureHandle specularAlbedo, const engine::Light& light,
                                                glm::vec3 axis, const SpotRsmFit& fit, float cosOuter,
                                                float cosInner, float lodTexels) {
    viewProjection_ = fit.viewProjection;
    // A texel's side on the image plane at 1 m is 2 tan / size: its area there is the solid angle
    // of the texel on the axis. texelArea_ is that area at the far plane (for the surfels' size).
    const float texel = 2.0f * fit.tanHalfAngle / float(size_);
    texelArea_ = texel * texel * fit.farPlane * fit.farPlane;
    SpotRsmUniforms u;
    u.lightViewProjection = viewProjection_;
    u.lightPosition =
        glm::vec4(light.position, light.range > 0.0f ? 1.0f / (light.range * light.range) : 0.0f);
    u.spotDirection = glm::vec4(axis, texel * texel);
    u.cone = glm::vec4(cosOuter, cosInner, 0, 0);
    u.intensity = glm::vec4(light.color * light.intensity, 0.0f);
    // A perspective texel grows with distance: an object is drawn for its nearest point to the light.
    const float errorPerMetre = lodTexels * texel;
    const glm::vec3 eye = light.position;
    const float nearPlane = fit.nearPlane;
    return draw(cmd, scene, specularAlbedo, &u, sizeof(u), 0.0f, [=](const engine::GpuDraw& d) {
        const glm::vec3 nearest = glm::clamp(eye, d.worldBounds.min, d.worldBounds.max);
        return errorPerMetre * std::max(nearPlane, glm::length(nearest - eye));
    });
}

template <class MaxError>
uint64_t ReflectiveShadowMap::draw(rhi::CommandList& cmd, const engine::GpuScene& scene,
                                   rhi::TextureHandle specularAlbedo, const void* uniforms, uint32_t bytes,
                                   float minObjectSize, MaxError&& maxError) {
    using namespace rhi;
    RenderPassDesc pass;
    pass.colors[0] = {normal_, 0, 0, LoadOp::Clear, {0, 1, 0, 0}};
    pass.colors[1] = {flux_, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
    pass.colorCount = 2;
    pass.depth = {depth_, 0, LoadOp::Clear, 1.0f};
    pass.debugName = light_ == RsmLight::Spot ? "spot rsm" : "rsm";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, uniforms, bytes);
    cmd.bindVertexBuffer(0, scene.vertices());
    cmd.bindVertexBuffer(engine::kDrawIndexSlot, scene.drawIndices());
    cmd.bindIndexBuffer(scene.indices(), IndexType::Uint32);
    cmd.bindTexture(3, specularAlbedo, linearSampler_);
    cmd.bindStorageBuffer(1, scene.drawRecords());
    // Room for every draw once; a frame that draws the map again grows it (MultiDraw::add).
    multiDraw_.reserve(uint32_t(scene.draws().size()));
    const std::vector<engine::GpuDraw>& draws = scene.draws();
    uint64_t triangles = 0;
    for (const engine::DrawBatch& batch : scene.batches()) {
        bool any = false;
        for (uint32_t k = batch.first; k < batch.first + batch.count; ++k) {
            const engine::GpuDraw& d = draws[scene.batchedDraws()[k]];
            // The light's view holds the volume and, toward the light, its occluders (fit()):
            // nothing outside it can land in the map.
            if (d.worldSize < minObjectSize || d.worldBounds.outsideClipVolume(viewProjection_)) continue;
            const engine::DrawLod& lod = d.lodWithin(maxError(d));
            multiDraw_.add(lod, d.index);
            any = true;
            triangles += lod.indexCount / 3;
        }
        if (!any) continue; // every draw culled
        const engine::GpuDraw& first = draws[scene.batchedDraws()[batch.first]];
        cmd.bindTexture(2, first.baseColor, scene.materialSampler());
        cmd.bindTexture(4, first.metallicRoughnessMap, scene.materialSampler());
        multiDraw_.draw(cmd);
    }
    cmd.endRenderPass();
    return triangles;
}

} // namespace lpv::gi
