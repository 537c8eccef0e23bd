// Spot light shadow maps: which spots get one, their fit, and the depth pass.
#include "engine/render/SpotShadows.h"

#include "EngineShaders.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace lpv::engine {
namespace {

// Wider cones than this are clamped: a perspective map of a near-hemisphere spends its texels on
// the rim (the RSM's kMaxSpotRsmHalfAngle does the same).
constexpr float kMaxHalfAngle = 1.3f; // 74.5 degrees

float halfAngleOf(const GpuPunctualLight& light) {
    return std::clamp(std::acos(std::clamp(light.cone.x, -1.0f, 1.0f)), 0.01f, kMaxHalfAngle);
}

float luminance(glm::vec3 c) {
    return glm::dot(c, glm::vec3(0.2126f, 0.7152f, 0.0722f));
}

// The farthest corner of `box` from `p`: how far an infinite light's map must reach.
float farthestCorner(glm::vec3 p, const Bounds& box) {
    if (box.empty()) return 100.0f;
    const glm::vec3 far = glm::max(glm::abs(box.min - p), glm::abs(box.max - p));
    return glm::length(far);
}

} // namespace

glm::mat4 spotShadowViewProjection(const GpuPunctualLight& light, float reach) {
    const glm::vec3 position(light.positionRange);
    glm::vec3 axis(light.directionType);
    axis = glm::length(axis) > 0.0f ? glm::normalize(axis) : glm::vec3(0.0f, -1.0f, 0.0f);
    const glm::vec3 up = std::fabs(axis.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const float range = light.positionRange.w;
    const float farPlane = std::max(range > 0.0f ? range : reach, 0.1f);
    // Depth precision follows far / near, as for the spot RSMs: 1/500 keeps D32F within a
    // millimetre at 10 m.
    const float nearPlane = std::max(0.02f, farPlane / 500.0f);
    // 1% wider than the cone, so its rim lands inside the outermost texels.
    const float tanHalf = std::tan(halfAngleOf(light)) * 1.01f;
    const glm::mat4 view = glm::lookAt(position, position + axis, up);
    return glm::perspectiveRH_ZO(2.0f * std::atan(tanHalf), 1.0f, nearPlane, farPlane) * view;
}

SpotShadows::SpotShadows(rhi::Device& device) : device_(device) {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &shaders::spot_shadow_vert;
    d.fragment = &shaders::shadow_frag;
    d.vertexBuffers = {{sizeof(Vertex)}};
    d.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)}};
    d.depthTest = d.depthWrite = true;
    d.depthCompare = CompareOp::Less;
    d.depthBiasConstant = 2.0f;
    d.depthBiasSlope = 2.0f;
    d.depthFormat = Format::D32F;
    d.debugName = "spot shadow";
    pipeline_ = device.createPipeline(d);
}

SpotShadows::~SpotShadows() {
    device_.waitIdle();
    release();
    device_.destroy(pipeline_);
}

void SpotShadows::release() {
    for (rhi::TextureHandle& t : textures_)
        if (t) device_.destroy(t), t = {};
    maps_ = active_ = 0;
}

void SpotShadows::resize(uint32_t maps, uint32_t size) {
    using namespace rhi;
    device_.waitIdle();
    release();
    maps_ = std::min(maps, kMaxMaps);
    size_ = size;
    for (uint32_t k = 0; k < maps_; ++k)
        textures_[k] = device_.createTexture({TextureKind::Tex2D, Format::D32F, size, size, 1, 1,
                                              kTextureDepthTarget | kTextureSampled,
                                              "spot shadow map " + std::to_string(k), "render.shadow"});
    uniforms_ = {};
}

uint64_t SpotShadows::render(rhi::CommandList& cmd, const GpuScene& scene,
                             std::span<const GpuPunctualLight> lights, const CameraMatrices& camera,
                             const Bounds& sceneBounds) {
    using namespace rhi;
    // The most important spots, best first (insertion into a fixed array: no allocation).
    std::array<uint32_t, kMaxMaps> chosen{};
    std::array<float, kMaxMaps> importance{};
    uint32_t count = 0;
    for (uint32_t i = 0; i < lights.size() && maps_ > 0; ++i) {
        const GpuPunctualLight& l = lights[i];
        if (l.directionType.w < 1.5f) continue; // a point light
        const float power = luminance(glm::vec3(l.colorIntensity)) * l.colorIntensity.w;
        if (!(power > 0.0f)) continue;
        const glm::vec3 position(l.positionRange);
        const float range = l.positionRange.w;
        if (range > 0.0f) {
            Bounds reach;
            reach.add(position - glm::vec3(range));
            reach.add(position + glm::vec3(range));
            if (reach.outsideClipVolume(camera.viewProjection)) continue;
        }
        const glm::vec3 d = position - camera.position;
        const float score = power / std::max(glm::dot(d, d), 1.0f);
        uint32_t at = count;
        while (at > 0 && importance[at - 1] < score)
            --at;
        if (at >= maps_) continue;
        for (uint32_t k = std::min(count, maps_ - 1); k > at; --k)
            chosen[k] = chosen[k - 1], importance[k] = importance[k - 1];
        chosen[at] = i;
        importance[at] = score;
        count = std::min(count + 1, maps_);
    }

    active_ = count;
    uniforms_.light = glm::ivec4(-1);
    uint64_t triangles = 0;
    for (uint32_t k = 0; k < count; ++k) {
        const GpuPunctualLight& l = lights[chosen[k]];
        const glm::mat4 viewProjection =
            spotShadowViewProjection(l, farthestCorner(glm::vec3(l.positionRange), sceneBounds));
        uniforms_.viewProjection[k] = viewProjection;
        uniforms_.light[int(k)] = int(chosen[k]);
        uniforms_.texelAtMetre[int(k)] = 2.0f * std::tan(halfAngleOf(l)) * 1.01f / float(size_);
        RenderPassDesc pass;
        pass.depth = {textures_[k], 0, LoadOp::Clear, 1.0f};
        pass.debugName = "spot shadow";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(pipeline_);
        cmd.pushUniforms(2, &viewProjection, sizeof(viewProjection));
        cmd.bindVertexBuffer(0, scene.vertices());
        cmd.bindIndexBuffer(scene.indices(), IndexType::Uint32);
        for (const GpuDraw& d : scene.draws()) {
            if (d.worldBounds.outsideClipVolume(viewProjection)) continue;
            cmd.pushUniforms(1, &d.uniforms, sizeof(d.uniforms));
            cmd.drawIndexed(d.lods[0].indexCount, 1, d.lods[0].firstIndex);
            triangles += d.lods[0].indexCount / 3;
        }
        cmd.endRenderPass();
    }
    work_ = {};
    work_.primitives = triangles;
    work_.texelsWritten = uint64_t(size_) * size_ * count;
    work_.bytesMoved = work_.texelsWritten * 4 + triangles * 3 * sizeof(Vertex);
    return triangles;
}

} // namespace lpv::engine
