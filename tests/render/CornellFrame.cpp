// Cornell box frames for the render and GI tests.
#include "CornellFrame.h"

#include "../support/TestDevice.h"

#include "engine/config/Config.h"
#include "engine/render/SpecularAlbedo.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace lpv::test {
namespace {

// A stored sRGB byte (as [0,1]) in linear light.
float linearFromSrgb(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

} // namespace

float luminance(glm::vec4 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec4& t : image.texels)
        sum += luminance(t);
    return sum / double(image.texels.size());
}

double meanLuminanceDifference(const Image& a, const Image& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.texels.size(); ++i)
        sum += std::fabs(double(luminance(a.texels[i])) - double(luminance(b.texels[i])));
    return sum / double(a.texels.size());
}

LuminanceChange luminanceChange(const Image& ref, const Image& image) {
    const double mean = meanLuminance(ref);
    if (image.texels.size() != ref.texels.size() || !(mean > 0.0))
        throw std::invalid_argument("luminanceChange: images of different sizes, or a black reference");
    return {meanLuminance(image) / mean - 1.0, meanLuminanceDifference(ref, image) / mean};
}

bool CornellFrame::pixelOf(glm::vec3 world, uint32_t& x, uint32_t& y) const {
    const glm::vec4 clip = camera.viewProjection * glm::vec4(world, 1.0f);
    if (clip.w <= 0.0f) return false;
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    if (std::fabs(ndc.x) >= 1.0f || std::fabs(ndc.y) >= 1.0f) return false;
    x = uint32_t((ndc.x * 0.5f + 0.5f) * float(width));
    y = uint32_t((ndc.y * 0.5f + 0.5f) * float(height));
    // Visible when the depth buffer holds (nearly) this point's depth.
    return std::fabs(depth.at(x, y).x - ndc.z) < 2e-3f;
}

glm::vec3 CornellFrame::worldAt(uint32_t x, uint32_t y) const {
    const glm::vec2 uv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
    const glm::vec4 w = camera.invViewProjection * glm::vec4(uv * 2.0f - 1.0f, depth.at(x, y).x, 1.0f);
    return glm::vec3(w) / w.w;
}

glm::vec3 CornellFrame::linearAlbedoAt(uint32_t x, uint32_t y) const {
    const glm::vec4 a = albedo.at(x, y);
    return {linearFromSrgb(a.r), linearFromSrgb(a.g), linearFromSrgb(a.b)};
}

glm::vec3 CornellFrame::diffuseKept(uint32_t x, uint32_t y) const {
    const glm::vec4 n = normal.at(x, y);
    const glm::vec3 toEye = glm::normalize(camera.position - worldAt(x, y));
    const float cosView = std::max(glm::dot(glm::normalize(glm::vec3(n)), toEye), 0.0f);
    const engine::SpecularAlbedo lobe =
        engine::specularAlbedoTable().at(cosView, std::clamp(n.a, 0.0f, 1.0f));
    // F0: 4% for dielectrics, the albedo for metals (albedo's alpha: metallic).
    const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), linearAlbedoAt(x, y), albedo.at(x, y).a);
    return 1.0f - (f0 * lobe.scale + lobe.bias);
}

CornellFrame renderSceneFrame(rhi::Device& device, engine::Scene scene,
                              const std::vector<std::string>& settings,
                              const std::function<void(engine::Renderer&)>& prepare, uint32_t width,
                              uint32_t height, int frames, glm::vec3 cameraOffset) {
    engine::Config config;
    for (const std::string& s : settings) {
        if (s.ends_with(".toml"))
            config.loadFile(s);
        else
            config.applyOverride(s, "test");
    }
    CornellFrame f;
    f.scene = std::move(scene);
    f.width = width;
    f.height = height;
    {
        engine::Renderer renderer(device, width, height);
        renderer.setScene(f.scene);
        if (prepare) prepare(renderer);
        gi::LightPropagationVolume lpv(device, platforms::loadPlatformProfile("pc"));
        engine::Camera camera = *f.scene.camera;
        camera.position += cameraOffset;
        f.camera = engine::cameraMatrices(camera, float(width) / float(height));
        for (int i = 0; i < frames; ++i) {
            if (const gi::GiConfigResult r = gi::updateFromConfig(lpv, config, renderer, f.camera); !r)
                throw std::runtime_error(r.message());
            rhi::CommandList& cmd = device.beginFrame();
            // The LPV is always the indirect provider here, so GI off means no indirect light at all.
            renderer.render(cmd, f.camera, config, nullptr, &lpv);
            device.endFrame();
        }
        device.waitIdle();
        f.output = readImage(device, renderer.output());
        f.hdr = readImage(device, renderer.hdr());
        f.depth = readImage(device, renderer.gbuffer().depth);
        f.glossy = readImage(device, renderer.glossy());
        f.indirect = readImage(device, renderer.indirect());
        f.albedo = readImage(device, renderer.gbuffer().albedo);
        f.normal = readImage(device, renderer.gbuffer().normal);
        f.indirectDivisor = renderer.indirectDivisor();
        if (lpv.settings().enabled)
            for (uint32_t c = 0; c < lpv.cascadeCount(); ++c) {
                f.cascadeGrids.push_back(lpv.cascadeGrid(c));
                std::array<Image, 3> v;
                for (uint32_t ch = 0; ch < 3; ++ch)
                    v[ch] = readImage(device, lpv.cascadeResult(c)[ch]);
                f.cascadeVolumes.push_back(std::move(v));
                const rhi::TextureHandle faces = lpv.lookupFaces(c);
                f.cascadeFaces.push_back(faces ? readImage(device, faces) : Image{});
            }
    }
    return f;
}

Image renderHdrAfterFrames(rhi::Device& device, const engine::Scene& scene, int frames,
                           const std::function<const engine::Config&(int)>& configFor) {
    engine::Renderer renderer(device, 320, 240);
    renderer.setScene(scene);
    gi::LightPropagationVolume lpv(device, platforms::loadPlatformProfile("pc"));
    const engine::CameraMatrices camera = engine::cameraMatrices(*scene.camera, 320.0f / 240.0f);
    for (int i = 0; i < frames; ++i) {
        const engine::Config& config = configFor(i);
        if (const gi::GiConfigResult r = gi::updateFromConfig(lpv, config, renderer, camera); !r)
            throw std::runtime_error(r.message());
        rhi::CommandList& cmd = device.beginFrame();
        renderer.render(cmd, camera, config, nullptr, &lpv);
        device.endFrame();
    }
    device.waitIdle();
    return readImage(device, renderer.hdr());
}

CornellFrame renderAtriumIndirect(rhi::Device& device, const engine::Scene& scene,
                                  const std::string& setting) {
    return renderSceneFrame(
        device, scene,
        {"gi.enabled=true", "render.debug_view=indirect", "gi.cell_size=1.0", "render.ssao=false", setting});
}

CornellFrame renderCornell(rhi::Device& device, const std::vector<std::string>& settings,
                           std::optional<glm::vec3> sunDirection, uint32_t width, uint32_t height, int frames,
                           glm::vec3 cameraOffset) {
    return renderSceneFrame(
        device, engine::buildCornellBox(), settings,
        [&](engine::Renderer& renderer) {
            if (sunDirection) renderer.sun().direction = glm::normalize(*sunDirection);
        },
        width, height, frames, cameraOffset);
}

FramesOnBothApis renderOnGlAndVulkan(const engine::Scene& scene, const std::vector<std::string>& settings,
                                     const std::function<void(engine::Renderer&)>& prepare, int frames) {
    FramesOnBothApis out;
    {
        TestDevice device(backendByName("gl-egl"));
        out.gl = renderSceneFrame(*device, scene, settings, prepare, 320, 240, frames);
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        out.vk = renderSceneFrame(*device, scene, settings, prepare, 320, 240, frames);
        device.expectSilent();
    }
    return out;
}

} // namespace lpv::test
