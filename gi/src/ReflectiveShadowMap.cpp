// RSM fit and pass.
#include "gi/ReflectiveShadowMap.h"

#include "GiShaders.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace lpv::gi {
namespace {
struct RsmUniforms {
    glm::mat4 lightViewProjection;
    glm::vec4 lightDirection;
    glm::vec4 fluxScale;
};
} // namespace

ReflectiveShadowMap::ReflectiveShadowMap(rhi::Device& device, uint32_t size) : device_(device), size_(size) {
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
    d.vertex = &shaders::rsm_vert;
    d.fragment = &shaders::rsm_frag;
    d.vertexBuffers = {{sizeof(engine::Vertex)}};
    d.attributes = {{0, VertexFormat::Float3, offsetof(engine::Vertex, position)},
                    {1, VertexFormat::Float3, offsetof(engine::Vertex, normal)},
                    {2, VertexFormat::Float2, offsetof(engine::Vertex, uv)}};
    d.depthTest = d.depthWrite = true;
    d.depthCompare = CompareOp::Less;
    d.colorFormats = {Format::RGBA16F, Format::RGBA16F};
    d.depthFormat = Format::D32F;
    d.debugName = "rsm";
    pipeline_ = device.createPipeline(d);
}

ReflectiveShadowMap::~ReflectiveShadowMap() {
    device_.waitIdle();
    device_.destroy(depth_);
    device_.destroy(normal_);
    device_.destroy(flux_);
    device_.destroy(pipeline_);
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
    return viewProjection_;
}

void ReflectiveShadowMap::render(rhi::CommandList& cmd, const engine::GpuScene& scene,
                                 glm::vec3 lightDirection, glm::vec3 sunIrradiance, float minObjectSize) {
    using namespace rhi;
    RsmUniforms u;
    u.lightViewProjection = viewProjection_;
    u.lightDirection = glm::vec4(glm::normalize(lightDirection), 0.0f);
    u.fluxScale = glm::vec4(sunIrradiance * texelArea_, 0.0f);
    RenderPassDesc pass;
    pass.colors[0] = {normal_, 0, 0, LoadOp::Clear, {0, 1, 0, 0}};
    pass.colors[1] = {flux_, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
    pass.colorCount = 2;
    pass.depth = {depth_, 0, LoadOp::Clear, 1.0f};
    pass.debugName = "rsm";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindVertexBuffer(0, scene.vertices());
    cmd.bindIndexBuffer(scene.indices(), IndexType::Uint32);
    for (const engine::GpuDraw& d : scene.draws()) {
        if (d.worldSize < minObjectSize) continue;
        cmd.pushUniforms(1, &d.uniforms, sizeof(d.uniforms));
        cmd.bindTexture(2, d.baseColor, scene.materialSampler());
        cmd.drawIndexed(d.indexCount, 1, d.firstIndex);
    }
    cmd.endRenderPass();
}

} // namespace lpv::gi
