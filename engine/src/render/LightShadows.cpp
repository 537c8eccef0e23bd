// Spot and point light shadow maps: which lights get one, their views, the atlas and the depth pass.
#include "engine/render/LightShadows.h"

#include "EngineShaders.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

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

bool isSpot(const GpuPunctualLight& l) {
    return l.directionType.w > 1.5f;
}

// The farthest corner of `box` from `p`: how far an infinite light's map must reach.
float farthestCorner(glm::vec3 p, const Bounds& box) {
    if (box.empty()) return 100.0f;
    return glm::length(glm::max(glm::abs(box.min - p), glm::abs(box.max - p)));
}

// A square perspective view from `position` along `axis` with sides at tanHalf, reaching `range`
// (or `reach` for 0).
glm::mat4 perspectiveView(glm::vec3 position, glm::vec3 axis, float tanHalf, float range, float reach) {
    const glm::vec3 up = std::fabs(axis.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const float farPlane = std::max(range > 0.0f ? range : reach, 0.1f);
    // Depth precision follows far / near, as for the spot RSMs: 1/500 keeps D32F within a
    // millimetre at 10 m.
    const float nearPlane = std::max(0.02f, farPlane / 500.0f);
    const glm::mat4 view = glm::lookAt(position, position + axis, up);
    return glm::perspectiveRH_ZO(2.0f * std::atan(tanHalf), 1.0f, nearPlane, farPlane) * view;
}

// Whether what view `a` holds can lie in view `b`: false when the corners of one's clip volume all
// lie beyond one plane of the other's. Conservative: two frusta that pass each other by an edge
// count as overlapping.
bool viewsMayOverlap(const glm::mat4& a, const glm::mat4& b) {
    const auto corners = [](const glm::mat4& viewProjection) {
        const glm::mat4 toWorld = glm::inverse(viewProjection);
        std::array<glm::vec3, 8> c;
        for (int i = 0; i < 8; ++i) {
            const glm::vec4 p = toWorld * glm::vec4((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f,
                                                    (i & 4) ? 1.0f : 0.0f, 1.0f);
            c[size_t(i)] = glm::vec3(p) / p.w;
        }
        return c;
    };
    return !outsideClipVolume(corners(a), b) && !outsideClipVolume(corners(b), a);
}

// The `capacity` most important lights of `lights` for which `wanted` holds, best first, into
// `out` (a fixed array: no allocation); returns how many. A light in `kept` (it had a map last
// frame) counts LightShadows::kKeepFactor times its importance.
template <typename Wanted>
uint32_t mostImportant(std::span<const GpuPunctualLight> lights, const CameraMatrices& camera,
                       uint32_t capacity, Wanted&& wanted, std::span<const uint32_t> kept,
                       std::span<uint32_t> out) {
    std::array<float, LightShadowUniforms::kMaxLights> importance{};
    capacity = std::min<uint32_t>({capacity, uint32_t(out.size()), uint32_t(importance.size())});
    uint32_t count = 0;
    for (uint32_t i = 0; i < lights.size() && capacity > 0; ++i) {
        const GpuPunctualLight& l = lights[i];
        if (!wanted(l)) continue;
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
        const bool hadMap = std::find(kept.begin(), kept.end(), i) != kept.end();
        const float score =
            power / std::max(glm::dot(d, d), 1.0f) * (hadMap ? LightShadows::kKeepFactor : 1.0f);
        uint32_t at = count;
        while (at > 0 && importance[at - 1] < score)
            --at;
        if (at >= capacity) continue;
        for (uint32_t k = std::min(count, capacity - 1); k > at; --k)
            out[k] = out[k - 1], importance[k] = importance[k - 1];
        out[at] = i;
        importance[at] = score;
        count = std::min(count + 1, capacity);
    }
    return count;
}

} // namespace

glm::mat4 spotShadowViewProjection(const GpuPunctualLight& light, float reach) {
    glm::vec3 axis(light.directionType);
    axis = glm::length(axis) > 0.0f ? glm::normalize(axis) : glm::vec3(0.0f, -1.0f, 0.0f);
    // 1% wider than the cone, so its rim lands inside the outermost texels.
    return perspectiveView(glm::vec3(light.positionRange), axis, std::tan(halfAngleOf(light)) * 1.01f,
                           light.positionRange.w, reach);
}

glm::mat4 pointShadowFaceViewProjection(const GpuPunctualLight& light, uint32_t face, float tanHalfAngle,
                                        float reach) {
    glm::vec3 axis(0.0f);
    axis[int(face / 2) % 3] = face % 2 == 0 ? 1.0f : -1.0f;
    return perspectiveView(glm::vec3(light.positionRange), axis, tanHalfAngle, light.positionRange.w, reach);
}

LightShadows::LightShadows(rhi::Device& device)
    : device_(device), draws_(device, "light shadow", "render.draw_commands") {
    using namespace rhi;
    GraphicsPipelineDesc d;
    d.vertex = &shaders::light_shadow_vert;
    d.fragment = &shaders::shadow_frag;
    d.vertexBuffers = {{sizeof(Vertex)}};
    d.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)}};
    addDrawIndexStream(d);
    d.depthTest = d.depthWrite = true;
    d.depthCompare = CompareOp::Less;
    d.depthBiasConstant = 2.0f;
    d.depthBiasSlope = 2.0f;
    d.depthFormat = Format::D32F;
    d.debugName = "light shadow";
    pipeline_ = device.createPipeline(d);
}

LightShadows::~LightShadows() {
    device_.waitIdle();
    release();
    device_.destroy(pipeline_);
}

void LightShadows::release() {
    if (atlas_) device_.destroy(atlas_);
    atlas_ = {};
    spots_ = pointLights_ = views_ = atlasWidth_ = atlasHeight_ = 0;
    uniforms_ = {};
}

void LightShadows::resize(uint32_t spots, uint32_t pointLights, uint32_t tileSize) {
    using namespace rhi;
    device_.waitIdle();
    release();
    spots_ = std::min(spots, kMaxSpots);
    pointLights_ = std::min(pointLights, kMaxPointLights);
    tileSize_ = tileSize;
    keptCount_ = 0; // a scene change renumbers the lights
    const uint32_t tiles = spots_ + 6 * pointLights_;
    if (tiles == 0) return;
    atlasWidth_ = std::min(tiles, kTilesPerRow) * tileSize;
    atlasHeight_ = ((tiles + kTilesPerRow - 1) / kTilesPerRow) * tileSize;
    atlas_ =
        device_.createTexture({TextureKind::Tex2D, Format::D32F, atlasWidth_, atlasHeight_, 1, 1,
                               kTextureDepthTarget | kTextureSampled, "light shadow atlas", "render.shadow"});
}

uint64_t LightShadows::drawView(rhi::CommandList& cmd, const GpuScene& scene, uint32_t view, bool draw) {
    using namespace rhi;
    const glm::mat4& viewProjection = uniforms_.viewProjection[view];
    const uint32_t x = (view % kTilesPerRow) * tileSize_, y = (view / kTilesPerRow) * tileSize_;
    uniforms_.tile[view] =
        glm::vec4(float(x) / float(atlasWidth_), float(y) / float(atlasHeight_),
                  float(tileSize_) / float(atlasWidth_), float(tileSize_) / float(atlasHeight_));
    if (!draw) return 0;
    cmd.setViewport({float(x), float(y), float(tileSize_), float(tileSize_), 0.0f, 1.0f});
    cmd.setScissor(int32_t(x), int32_t(y), tileSize_, tileSize_);
    cmd.pushUniforms(2, &viewProjection, sizeof(viewProjection));
    cmd.bindStorageBuffer(1, scene.drawRecords());
    uint64_t triangles = 0;
    for (const GpuDraw& d : scene.draws()) {
        if (d.worldBounds.outsideClipVolume(viewProjection)) continue;
        draws_.add(d.lods[0], d.index);
        triangles += d.lods[0].indexCount / 3;
    }
    draws_.draw(cmd);
    return triangles;
}

uint64_t LightShadows::render(rhi::CommandList& cmd, const GpuScene& scene,
                              std::span<const GpuPunctualLight> lights, const CameraMatrices& camera,
                              const Bounds& sceneBounds) {
    using namespace rhi;
    std::array<uint32_t, kMaxSpots> spots{};
    std::array<uint32_t, kMaxPointLights> points{};
    const std::span<const uint32_t> kept(kept_.data(), keptCount_);
    const uint32_t spotCount = mostImportant(lights, camera, spots_, isSpot, kept, spots);
    const uint32_t pointCount = mostImportant(
        lights, camera, pointLights_, [](const GpuPunctualLight& l) { return !isSpot(l); }, kept, points);
    keptCount_ = 0;
    for (uint32_t k = 0; k < spotCount; ++k)
        kept_[keptCount_++] = spots[k];
    for (uint32_t k = 0; k < pointCount; ++k)
        kept_[keptCount_++] = points[k];

    uniforms_.count = glm::ivec4(int(spotCount + pointCount), 0, 0, 0);
    views_ = drawnViews_ = 0;
    work_ = {};
    if (spotCount + pointCount == 0) return 0;
    // A point light's faces: a texel and a half wider than 90 degrees per side, so the 3x3 PCF of
    // a pixel near a face's edge stays inside the face its direction picks.
    const float cubeTan = 1.0f + 3.0f / float(tileSize_);
    uint32_t n = 0;
    for (uint32_t k = 0; k < spotCount + pointCount; ++k) {
        const bool spot = k < spotCount;
        const uint32_t index = spot ? spots[k] : points[k - spotCount];
        const GpuPunctualLight& l = lights[index];
        const float reach = farthestCorner(glm::vec3(l.positionRange), sceneBounds);
        const uint32_t faces = spot ? 1 : 6;
        uniforms_.light[n] = glm::ivec4(int(index), int(views_), int(faces), 0);
        const float tanHalf = spot ? std::tan(halfAngleOf(l)) * 1.01f : cubeTan;
        uniforms_.params[n] = glm::vec4(2.0f * tanHalf / float(tileSize_), 0.0f, 0.0f, 0.0f);
        for (uint32_t f = 0; f < faces; ++f)
            uniforms_.viewProjection[views_ + f] = spot ? spotShadowViewProjection(l, reach)
                                                        : pointShadowFaceViewProjection(l, f, cubeTan, reach);
        views_ += faces;
        ++n;
    }

    RenderPassDesc pass;
    pass.depth = {atlas_, 0, LoadOp::Clear, 1.0f};
    pass.debugName = "light shadows";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline_);
    cmd.bindVertexBuffer(0, scene.vertices());
    cmd.bindVertexBuffer(kDrawIndexSlot, scene.drawIndices());
    cmd.bindIndexBuffer(scene.indices(), IndexType::Uint32);
    // Each view's draws in one multi-draw. Room for every draw once: the views' culling leaves a
    // share each, and a frame that needs more grows it to what it used (MultiDraw::add), not to
    // every draw in every view (a 20,000-draw level's 16 views would be 25 MB).
    draws_.reserve(uint32_t(scene.draws().size()));
    uint64_t triangles = 0;
    for (uint32_t v = 0; v < views_; ++v) {
        // A view the camera's does not overlap (a point light's face turned away from it, a spot
        // beside it whose range still reaches the view) lights no pixel the lighting pass shades:
        // a visible pixel in a face's directions lies in that face's view. Its tile stays cleared.
        const bool seen = viewsMayOverlap(uniforms_.viewProjection[v], camera.viewProjection);
        triangles += drawView(cmd, scene, v, seen);
        drawnViews_ += seen ? 1 : 0;
    }
    cmd.endRenderPass();
    work_.primitives = triangles;
    work_.texelsWritten = uint64_t(tileSize_) * tileSize_ * views_;
    work_.bytesMoved = work_.texelsWritten * 4 + triangles * 3 * sizeof(Vertex);
    return triangles;
}

} // namespace lpv::engine
