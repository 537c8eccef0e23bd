// The reflective shadow map of the sun, fitted tightly around the light volume and snapped to its
// own texels, so a moving camera (and volume) shifts the RSM by whole texels and it does not swim.
// Targets: depth, world normal, reflected flux per texel.
#pragma once

#include "engine/render/GpuScene.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>

namespace lpv::gi {

class ReflectiveShadowMap {
public:
    ReflectiveShadowMap(rhi::Device& device, uint32_t size);
    ~ReflectiveShadowMap();
    ReflectiveShadowMap(const ReflectiveShadowMap&) = delete;
    ReflectiveShadowMap& operator=(const ReflectiveShadowMap&) = delete;

    uint32_t size() const { return size_; }
    // Fits the light's projection around `grid`; returns the light view-projection.
    glm::mat4 fit(const VolumeGrid& grid, glm::vec3 lightDirection);
    // Draws the objects at least `minObjectSize` m across: a coarse cascade leaves out what is
    // small next to its cells (a finer cascade carries it).
    void render(rhi::CommandList& cmd, const engine::GpuScene& scene, glm::vec3 lightDirection,
                glm::vec3 sunIrradiance, float minObjectSize = 0.0f);

    const glm::mat4& lightViewProjection() const { return viewProjection_; }
    float texelArea() const { return texelArea_; }
    rhi::TextureHandle depth() const { return depth_; }
    rhi::TextureHandle normal() const { return normal_; }
    rhi::TextureHandle flux() const { return flux_; }

private:
    rhi::Device& device_;
    uint32_t size_;
    rhi::TextureHandle depth_, normal_, flux_;
    rhi::GraphicsPipelineHandle pipeline_;
    glm::mat4 viewProjection_{1.0f};
    float texelArea_ = 0.0f;
};

} // namespace lpv::gi
