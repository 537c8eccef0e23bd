// The renderer's hook for global illumination. Between the G-buffer and the lighting pass, the
// renderer asks the provider (the LPV in gi/) to fill the indirect-irradiance target and the glossy
// radiance target; without a provider they hold the constant render.ambient as a uniform sky. A
// provider may also light a participating medium (fog) with what it holds: the renderer then gives
// it the sun's shadow map and composes the medium over the lit frame.
#pragma once

#include "engine/render/CameraMatrices.h"
#include "engine/scene/Scene.h"
#include "rhi/CommandList.h"
#include "rhi/Handle.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>

namespace lpv::engine {

class FrameProfiler;

struct GBufferView {
    rhi::TextureHandle albedo; // RGBA8 sRGB: albedo, metallic in alpha
    rhi::TextureHandle normal; // RGBA16F: world normal, roughness in alpha
    rhi::TextureHandle depth;  // D32F, sampled
    rhi::TextureHandle ao;     // R32F, 1 = unoccluded
    uint32_t width = 0, height = 0;
};

// The sun as the renderer's shadow pass left it, for a provider that lights a medium with it.
struct SunShadowView {
    rhi::TextureHandle shadowMap;   // D32F, sampled with a compare sampler; null: no shadow
    glm::mat4 viewProjection{1.0f}; // world to shadow map space: xy in [-1, 1], depth in [0, 1]
    glm::vec3 direction{0, -1, 0};  // where the light travels (normalized)
    glm::vec3 radiance{0.0f};       // irradiance on a surface facing the sun
    float depthBias = 0.0f;         // subtracted from a point's depth before the compare
};

class IndirectLighting {
public:
    virtual ~IndirectLighting() = default;
    // Writes indirect irradiance (RGBA16F, linear, W/m^2-like units of the sun's) for every pixel
    // into `target`, and into `glossyTarget` (RGBA16F, linear) the radiance a glossy
    // surface gathers over its specular lobe, before the lobe's weight F0 x scale + bias
    // (SpecularAlbedo.h), which the lighting pass applies. The call must fully overwrite both. Both
    // are 1/resolutionDivisor() of the G-buffer per axis (rounded up): texel (x, y) holds the
    // answer for G-buffer pixel (x, y) * divisor. The irradiance's alpha holds that pixel's view
    // depth (its clip-space w; 0 where there is no surface): the lighting pass's rebuild places the
    // texel in space with it instead of fetching the G-buffer's depth; the glossy radiance's alpha
    // holds that pixel's normal, packed by shaders/rebuild_normal.glsl, which the rebuild compares
    // with the normal of the pixel it fills. Without a provider the first holds render.ambient,
    // the second render.ambient / pi (a uniform sky; no surface, so no rebuild).
    virtual void renderIndirect(rhi::CommandList& cmd, const CameraMatrices& camera,
                                const GBufferView& gbuffer, rhi::TextureHandle target,
                                rhi::TextureHandle glossyTarget, FrameProfiler* profiler) = 0;
    // Per axis, how much smaller than the frame the provider wants its two targets: 1 for every
    // pixel, 2 or 4 to light a quarter or a sixteenth of them. The lighting pass then rebuilds every
    // pixel's value from the four nearest with a joint bilateral filter (depth and normal), so
    // light does not bleed across silhouettes. Asked every frame before renderIndirect(); a change
    // remakes the targets on that frame.
    virtual uint32_t resolutionDivisor() const { return 1; }
    // Per axis, how much smaller than the frame the provider wants the medium's target, or 0 when
    // it lights no medium this frame (then renderMedium() is not called and the lighting pass
    // composes nothing). Asked every frame before renderMedium(); a change remakes the target.
    virtual uint32_t mediumDivisor() const { return 0; }
    // Fills `target` (RGBA16F, 1/mediumDivisor() of the G-buffer per axis, rounded up): texel t, for
    // G-buffer pixel t x divisor, holds in rgb the radiance the medium scatters toward the camera
    // along that pixel's ray up to its surface (or out of the scene), and in alpha the medium's
    // transmittance along it. The lighting pass writes surface x alpha + rgb, rebuilding the pixels
    // between texels with a depth-aware filter. Called after renderIndirect().
    virtual void renderMedium(rhi::CommandList& cmd, const CameraMatrices& camera, const GBufferView& gbuffer,
                              const SunShadowView& sun, rhi::TextureHandle target, FrameProfiler* profiler) {
        (void)cmd, (void)camera, (void)gbuffer, (void)sun, (void)target, (void)profiler;
    }
    // Draws debug views over the tone-mapped output (RGBA8 sRGB color target); none by default.
    virtual void renderDebugOverlay(rhi::CommandList& cmd, const CameraMatrices& camera,
                                    rhi::TextureHandle output) {
        (void)cmd, (void)camera, (void)output;
    }
    // True when the indirect light written by renderIndirect() already holds punctual light `index`
    // (of Renderer::punctualLights(); the LPV's analytic lights), so the lighting pass must not add
    // it again. Asked per light every frame: a provider may carry some lights and not others (the
    // LPV lights a spot light with its own RSM per pixel and carries only its bounce).
    virtual bool carriesPunctualLight(uint32_t index) const {
        (void)index;
        return false;
    }
    // At most how many point (spot) lights carriesPunctualLight() may leave to the lighting pass
    // while the provider's settings stay as they are: the renderer makes shadow maps for no more.
    // Unlimited by default.
    virtual uint32_t perPixelLightLimit(LightType type) const {
        (void)type;
        return std::numeric_limits<uint32_t>::max();
    }
};

} // namespace lpv::engine
