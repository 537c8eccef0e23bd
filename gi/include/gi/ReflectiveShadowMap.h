// A reflective shadow map. The sun's is fitted tightly around the light volume and snapped to its
// own texels, so a moving camera (and volume) shifts the RSM by whole texels and it does not swim.
// A spot light's is a perspective view from the light around its cone; a point light's is a cube
// of six such views of 90 degrees (SpotLightRsms).
// Targets: depth, world normal, reflected flux per texel.
#pragma once

#include "engine/render/GpuScene.h"
#include "engine/render/MultiDraw.h"
#include "engine/scene/Scene.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>

namespace lpv::gi {

enum class RsmLight { Sun, Spot };

// A perspective RSM cannot hold a cone wider than this half-angle (radians, 70 degrees); a wider
// spot's RSM sees the middle of its cone.
constexpr float kMaxSpotRsmHalfAngle = 1.2217305f;

// The frustum of a spot light's RSM: from the light along its axis, square, just around the outer
// cone (at most kMaxSpotRsmHalfAngle), out to the light's range or `reach` m (how far the volume
// needs it), whichever is nearer.
struct SpotRsmFit {
    glm::mat4 viewProjection{1.0f};
    glm::vec3 axis{0.0f, 0.0f, -1.0f}; // where the frustum looks
    float tanHalfAngle = 0.0f;         // of the frustum's sides
    float nearPlane = 0.0f, farPlane = 0.0f;
};
SpotRsmFit fitSpotRsm(const engine::Light& spot, float reach);

// A point light's RSM is a cube: six faces, +x, -x, +y, -y, +z, -z from the light.
inline constexpr uint32_t kCubeFaces = 6;
glm::vec3 cubeFaceAxis(uint32_t face);
// Face `face` of a point light's cube RSM: a square frustum of exactly 90 degrees along
// cubeFaceAxis(face), so the six tile the sphere around the light without overlap.
SpotRsmFit fitCubeFace(const engine::Light& point, uint32_t face, float reach);

class ReflectiveShadowMap {
public:
    ReflectiveShadowMap(rhi::Device& device, uint32_t size, RsmLight light = RsmLight::Sun);
    ~ReflectiveShadowMap();
    ReflectiveShadowMap(const ReflectiveShadowMap&) = delete;
    ReflectiveShadowMap& operator=(const ReflectiveShadowMap&) = delete;

    uint32_t size() const { return size_; }
    // Fits the light's projection around `grid`; returns the light view-projection.
    glm::mat4 fit(const VolumeGrid& grid, glm::vec3 lightDirection);
    // Draws the objects at least `minObjectSize` m across: a coarse cascade leaves out what is
    // small next to its cells (a finer cascade carries it). Objects outside the light's view are
    // skipped. Each object is drawn at the coarsest level of detail that strays at most
    // `lodTexels` of this map's texels from its mesh (0: full meshes). Returns the triangles drawn
    // (the pass's work).
    // `specularAlbedo` (engine::SpecularAlbedoTexture) gives the share of the light the materials'
    // specular layer leaves to their diffuse base (gi/shaders/rsm_diffuse.glsl).
    uint64_t record(rhi::CommandList& cmd, const engine::GpuScene& scene, rhi::TextureHandle specularAlbedo,
                    glm::vec3 lightDirection, glm::vec3 sunIrradiance, float minObjectSize = 0.0f,
                    float lodTexels = 0.0f);
    // A spot RSM (RsmLight::Spot): fits it to `spot` (fitSpotRsm) and draws the scene in its view,
    // with levels of detail as record() (a texel measured at the object's nearest point to the
    // light). Returns the triangles drawn.
    uint64_t recordSpot(rhi::CommandList& cmd, const engine::GpuScene& scene,
                        rhi::TextureHandle specularAlbedo, const engine::Light& spot, float reach,
                        float lodTexels = 0.0f);
    // Face `face` of a point light's cube RSM (RsmLight::Spot maps; fitCubeFace): the light's
    // intensity through every texel of the face, no cone edge. Returns the triangles drawn.
    uint64_t recordCubeFace(rhi::CommandList& cmd, const engine::GpuScene& scene,
                            rhi::TextureHandle specularAlbedo, const engine::Light& point, uint32_t face,
                            float reach, float lodTexels = 0.0f);

    const glm::mat4& lightViewProjection() const { return viewProjection_; }
    float texelArea() const { return texelArea_; }
    rhi::TextureHandle depth() const { return depth_; }
    rhi::TextureHandle normal() const { return normal_; }
    rhi::TextureHandle flux() const { return flux_; }

private:
    // A perspective RSM of `light` (spot or point) through `fit` along `axis`, weighted by the cone
    // from cosOuter to cosInner (smoothstep of the cosine to the axis).
    uint64_t recordPerspective(rhi::CommandList& cmd, const engine::GpuScene& scene,
                               rhi::TextureHandle specularAlbedo, const engine::Light& light, glm::vec3 axis,
                               const SpotRsmFit& fit, float cosOuter, float cosInner, float lodTexels);
    // `maxError(draw)`: the error (m) the draw's level of detail may have.
    template <class MaxError>
    uint64_t draw(rhi::CommandList& cmd, const engine::GpuScene& scene, rhi::TextureHandle specularAlbedo,
                  const void* uniforms, uint32_t bytes, float minObjectSize, MaxError&& maxError);

    rhi::Device& device_;
    uint32_t size_;
    RsmLight light_;
    rhi::TextureHandle depth_, normal_, flux_;
    rhi::GraphicsPipelineHandle pipeline_;
    rhi::SamplerHandle linearSampler_; // the specular albedo table's
    engine::MultiDraw multiDraw_;
    glm::mat4 viewProjection_{1.0f};
    float texelArea_ = 0.0f;
    float texelSide_ = 0.0f; // of the sun's orthographic map (m)
};

} // namespace lpv::gi
