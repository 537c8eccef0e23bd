// Renders the Cornell box (or another scene) through the engine's renderer (and the LPV when
// gi.enabled) on a test device and reads back what the render tests look at.
#pragma once

#include "../support/Image.h"

#include "engine/config/Config.h"
#include "engine/render/CameraMatrices.h"
#include "engine/render/Renderer.h"
#include "engine/scene/Scene.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <glm/vec3.hpp>

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace lpv::test {

struct CornellFrame {
    Image output; // tone-mapped sRGB, as [0,1] floats of the stored bytes
    Image hdr;    // linear HDR before tone mapping (or the debug view)
    Image depth;
    Image glossy;   // the glossy radiance target (linear, before the specular weight)
    Image indirect; // the indirect irradiance target (linear)
    Image albedo;   // the G-buffer's albedo, as [0,1] floats of the stored sRGB bytes; alpha: metallic
    Image normal;   // the G-buffer's world normal; alpha: roughness
    // The two targets above are 1/indirectDivisor of the frame per axis (gi.resolution): texel t
    // holds the answer for pixel t x indirectDivisor.
    uint32_t indirectDivisor = 1;
    engine::CameraMatrices camera;
    engine::Scene scene;
    uint32_t width = 0, height = 0;
    // With GI on: every cascade's placement and result volumes (R, G, B; RGBA16F unless encoded).
    std::vector<gi::VolumeGrid> cascadeGrids;
    std::vector<std::array<Image, 3>> cascadeVolumes;
    // With gi.occlusion: per cascade, the face transmittance its lookup keeps to (lpv_lookup.glsl's
    // keptInside), or an empty image where its lookup filters plainly (gi.lookup_occlusion=false).
    std::vector<Image> cascadeFaces;

    // The pixel a world point lands on; false when off screen or hidden behind other geometry.
    bool pixelOf(glm::vec3 world, uint32_t& x, uint32_t& y) const;
    // The surface point pixel (x, y)'s centre shows, from the read-back depth (not on the sky).
    glm::vec3 worldAt(uint32_t x, uint32_t y) const;
    // The G-buffer's albedo at pixel (x, y), linear.
    glm::vec3 linearAlbedoAt(uint32_t x, uint32_t y) const;
    // The share of the indirect light pixel (x, y)'s diffuse base keeps, per channel, as the
    // lighting pass takes it: 1 - the specular lobe's directional albedo (F0 x scale + bias of
    // engine/render/SpecularAlbedo.h's table at the pixel's view angle and roughness).
    glm::vec3 diffuseKept(uint32_t x, uint32_t y) const;
    // The glossy target's texel that holds pixel (x, y)'s answer, or its nearest.
    glm::vec4 glossyAt(uint32_t x, uint32_t y) const {
        return glossy.at(x / indirectDivisor, y / indirectDivisor);
    }
};

// `settings`: key=value overrides (e.g. "render.debug_view=ssao", "gi.enabled=true"), or the path of a
// TOML config file (ending in .toml) to load; applied in order, as the game applies --config and --set.
CornellFrame renderCornell(rhi::Device& device, const std::vector<std::string>& settings,
                           std::optional<glm::vec3> sunDirection = std::nullopt, uint32_t width = 320,
                           uint32_t height = 240, int frames = 1, glm::vec3 cameraOffset = glm::vec3(0.0f));

// `scene` from its own camera; `prepare` may change the renderer (its sun) before the frames.
CornellFrame renderSceneFrame(rhi::Device& device, engine::Scene scene,
                              const std::vector<std::string>& settings,
                              const std::function<void(engine::Renderer&)>& prepare = {},
                              uint32_t width = 320, uint32_t height = 240, int frames = 1,
                              glm::vec3 cameraOffset = glm::vec3(0.0f));

// The HDR target (or debug view) of `scene` from its own camera at 320x240 after `frames` frames,
// frame i under `configFor(i)`: for tests that change a setting mid-run.
Image renderHdrAfterFrames(rhi::Device& device, const engine::Scene& scene, int frames,
                           const std::function<const engine::Config&(int)>& configFor);

// The indirect light alone (render.debug_view=indirect, SSAO off) of `scene` (the atrium) with GI
// on at lpv_bench's cell size (1 m) and `setting` on top, for the atrium's GI accuracy tests.
CornellFrame renderAtriumIndirect(rhi::Device& device, const engine::Scene& scene,
                                  const std::string& setting);

// The same frame of `scene` on gl-egl and on Vulkan (each device's messages checked silent), for
// the tests that compare the two APIs.
struct FramesOnBothApis {
    CornellFrame gl, vk;
};
FramesOnBothApis renderOnGlAndVulkan(const engine::Scene& scene, const std::vector<std::string>& settings,
                                     const std::function<void(engine::Renderer&)>& prepare = {},
                                     int frames = 1);

float luminance(glm::vec4 c);
// The mean luminance of an image's texels.
double meanLuminance(const Image& image);
// The mean of |luminance(a) - luminance(b)| over two images of the same size.
double meanLuminanceDifference(const Image& a, const Image& b);
// `image` against `ref` (same size, some light in ref): its mean luminance's change and the mean
// difference per pixel, both relative to ref's mean (std::invalid_argument otherwise).
struct LuminanceChange {
    double meanShift = 0.0, meanDifference = 0.0;
};
LuminanceChange luminanceChange(const Image& ref, const Image& image);

} // namespace lpv::test
