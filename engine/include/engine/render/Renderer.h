// The deferred renderer: sun shadow map, spot and point light shadow maps (LightShadows),
// G-buffer (albedo, normal, emissive, depth), SSAO, indirect light (from an IndirectLighting
// provider or the ambient constant), HDR lighting and tone mapping to sRGB. Every pass goes through
// the RHI with a debug marker and a profiler scope. Targets are made at construction (the sun's shadow
// map and the indirect targets on the first frame, which knows their sizes), on resize and when a
// setting that sizes them changes, never in a steady-state frame.
#pragma once

#include "engine/config/Config.h"
#include "engine/profiler/WorkCounts.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/GpuScene.h"
#include "engine/render/IndirectLighting.h"
#include "engine/render/LightShadows.h"
#include "engine/render/MultiDraw.h"
#include "engine/render/SpecularAlbedoTexture.h"
#include "rhi/Device.h"

#include <glm/vec3.hpp>

#include <memory>
#include <vector>

namespace lpv::engine {

class FrameProfiler;

enum class DebugView { Final, Albedo, Normals, Depth, Ssao, Shadow, Indirect, Glossy, Specular, Fog };

struct SunLight {
    glm::vec3 direction{0.25f, -1.0f, -0.15f}; // where the light travels
    glm::vec3 radiance{20.0f};                 // irradiance on a surface facing the sun
};

// std140 block `Frame` of common.glsl.
struct FrameUniforms {
    glm::mat4 viewProjection;
    glm::mat4 invViewProjection;
    glm::mat4 view;
    glm::mat4 sunViewProjection;
    glm::vec4 cameraPosition;
    glm::vec4 sunDirection;
    glm::vec4 sunRadiance;
    glm::vec4 ambient;
    glm::vec4 viewport;
    glm::vec4 params;
    glm::ivec4 counts;
    glm::ivec4 medium; // x: the medium target's divisor (IndirectLighting::mediumDivisor), 0: none
};

// What the lighting pass adds per frame to rebuild every pixel's indirect and glossy light from
// targets smaller than the frame (IndirectLighting::resolutionDivisor() > 1): four neighbours'
// irradiance (with view depth), glossy radiance and normal and their weights, instead of one
// texel of irradiance and glossy.
WorkCounts indirectRebuildWork(uint64_t pixels);

class Renderer {
public:
    Renderer(rhi::Device& device, uint32_t width, uint32_t height);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void resize(uint32_t width, uint32_t height);
    // Uploads the scene (replacing the previous one) and takes its first directional light as the sun
    // (none: the sun gives no light).
    void setScene(const Scene& scene);
    SunLight& sun() { return sun_; }
    const SunLight& sun() const { return sun_; }
    const Bounds& sceneBounds() const { return bounds_; }
    // The scene's point and spot lights (as set by setScene()), for the GI to read every frame.
    const std::vector<Light>& punctualLights() const { return punctualLights_; }
    // The uploaded scene (null before setScene()); the GI draws its reflective shadow maps from it.
    const GpuScene* scene() const { return scene_.get(); }

    // Records one frame's passes into `cmd`. Reads render.* settings.
    void render(rhi::CommandList& cmd, const CameraMatrices& camera, const Config& config,
                FrameProfiler* profiler, IndirectLighting* indirect = nullptr);

    rhi::TextureHandle output() const { return targets_.output; } // RGBA8 sRGB, tone mapped
    rhi::TextureHandle hdr() const { return targets_.hdr; }       // RGBA16F linear, before tone mapping
    // RGBA16F linear: the radiance glossy surfaces reflect (before the specular weight; the ambient
    // constant / pi without GI), at 1/indirectDivisor() of the frame per axis, as the indirect
    // provider asked.
    rhi::TextureHandle glossy() const { return targets_.glossy; }
    // engine/render/SpecularAlbedo.h's table (RGBA16F, laid out as shaders/specular_albedo.glsl
    // reads it), for an indirect provider that weighs its lobes as the lighting pass does.
    rhi::TextureHandle specularAlbedoTexture() const { return specularAlbedo_->texture(); }
    // RGBA16F linear: the indirect irradiance the provider wrote (or the ambient constant), at
    // 1/indirectDivisor() of the frame per axis. This, glossy() and the sun's shadow map exist
    // from the first render() on (indirectDivisor() is 0 before).
    rhi::TextureHandle indirect() const { return targets_.indirect; }
    uint32_t indirectDivisor() const { return indirectDivisor_; }
    // RGBA16F linear: what the provider's medium scatters toward the camera (rgb) and lets through
    // (alpha), at 1/mediumDivisor() of the frame per axis; null while the provider lights no medium.
    rhi::TextureHandle medium() const { return targets_.medium; }
    uint32_t mediumDivisor() const { return mediumDivisor_; }
    GBufferView gbuffer() const;
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    const FrameUniforms& frameUniforms() const { return frame_; }
    // The spot and point lights' shadow maps (render.spot_shadows, render.point_shadows) as the
    // last frame chose and drew them.
    const LightShadows& lightShadows() const { return *lightShadows_; }

private:
    struct Targets {
        rhi::TextureHandle albedo, normal, emissive, depth, aoRaw, ao, indirect, glossy, hdr, output, shadow,
            medium;
    };
    void createTargets(uint32_t shadowSize);
    // The indirect and glossy targets at 1/divisor of the frame per axis (IndirectLighting).
    void createIndirectTargets(uint32_t divisor);
    // The medium's target at 1/divisor of the frame per axis (none for 0).
    void createMediumTarget(uint32_t divisor);
    void destroyTargets();
    void createPipelines();
    // The G-buffer pass without or with metallic-roughness and emissive maps (gbuffer_body.glsl).
    static rhi::GraphicsPipelineDesc gbufferPipelineDesc(bool materialMaps);
    // The point and spot lights the lighting pass lights itself (those `indirect` does not carry):
    // their count, and in `buffer` the buffer that holds them (the scene's, or directLights_ when
    // only some are left, refilled when that choice changes).
    uint32_t directLights(rhi::CommandList& cmd, const IndirectLighting* indirect, rhi::BufferHandle& buffer);

    rhi::Device& device_;
    uint32_t width_, height_, shadowSize_ = 0;
    uint32_t indirectDivisor_ = 0; // 0: no indirect targets yet (the first frame makes them)
    uint32_t mediumDivisor_ = 0;   // 0: no medium target
    Targets targets_;
    rhi::GraphicsPipelineHandle gbufferPipeline_, gbufferMappedPipeline_, shadowPipeline_, ssaoPipeline_,
        ssaoBlurPipeline_, lightingPipeline_, lightingShadowedPipeline_, tonemapPipeline_;
    rhi::SamplerHandle linearClamp_, pointClamp_, shadowCompare_;
    // The glossy term's weight per view angle and roughness (SpecularAlbedoTable), made once.
    std::unique_ptr<SpecularAlbedoTexture> specularAlbedo_;
    std::unique_ptr<GpuScene> scene_;
    Bounds bounds_;
    SunLight sun_;
    std::vector<Light> punctualLights_;
    // Made with the scene, sized for all its lights: a steady-state frame allocates nothing.
    rhi::BufferHandle directLights_;
    std::vector<uint32_t> directIndices_, uploadedIndices_; // into the scene's light records
    std::vector<GpuPunctualLight> directRecords_;
    std::unique_ptr<LightShadows> lightShadows_;
    uint32_t sceneSpots_ = 0, scenePointLights_ = 0; // no more shadow maps than the scene has lights
    FrameUniforms frame_{};
    MultiDraw shadowDraws_, gbufferDraws_;
};

} // namespace lpv::engine
