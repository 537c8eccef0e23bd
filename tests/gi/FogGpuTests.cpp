// The fog march (gi/FogMarch.h) against closed forms, on each backend: a homogeneous medium inside a
// volume of uniform radiance L scatters albedo x L x (1 - exp(-sigma d)) toward the camera along a
// ray of length d and lets exp(-sigma d) of the surface through; the sun's single scattering is
// albedo x E x phase x (1 - exp(-sigma d)); a ray that meets no surface stops at the scene's bounds;
// the sun's shadow map takes the shafts away. Through the renderer: fog of zero density leaves the
// frame as it is without fog, bit for bit; the fog debug view shows the medium's light alone; GL and
// Vulkan agree.
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/scene/BuiltinScenes.h"
#include "gi/FogMarch.h"

#include <doctest/doctest.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <numbers>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

constexpr uint32_t kWidth = 32, kHeight = 16;
constexpr float kCell = 50.0f; // 4 cells of 50 m around the camera hold every ray
constexpr uint32_t kCells = 4;

// A camera at the origin looking down -z, 90 degrees wide.
engine::CameraMatrices fogCamera() {
    engine::CameraMatrices c;
    c.position = glm::vec3(0.0f);
    c.forward = glm::vec3(0, 0, -1);
    c.view = glm::lookAt(c.position, c.position + c.forward, glm::vec3(0, 1, 0));
    c.projection = glm::perspectiveRH_ZO(glm::radians(90.0f), float(kWidth) / float(kHeight), 0.5f, 100.0f);
    c.viewProjection = c.projection * c.view;
    c.invViewProjection = glm::inverse(c.viewProjection);
    return c;
}

// What the march sees for pixel (x, y) at depth-buffer value `depth`: the direction and distance.
struct PixelRay {
    glm::vec3 direction;
    float length;
};
PixelRay pixelRay(const engine::CameraMatrices& c, uint32_t x, uint32_t y, float depth) {
    const glm::vec2 uv((float(x) + 0.5f) / float(kWidth), (float(y) + 0.5f) / float(kHeight));
    const glm::vec4 h = c.invViewProjection * glm::vec4(uv * 2.0f - 1.0f, depth, 1.0f);
    const glm::vec3 p = glm::vec3(h) / h.w - c.position;
    return {glm::normalize(p), glm::length(p)};
}

float henyeyGreenstein(float cosine, float g) {
    const float d = 1.0f + g * g - 2.0f * g * cosine;
    return (1.0f - g * g) / (4.0f * std::numbers::pi_v<float> * d * std::sqrt(d));
}

struct FogRig {
    rhi::Device& device;
    rhi::TextureHandle depth, shadow, target;
    std::array<rhi::TextureHandle, 3> volumes{};
    gi::FogMarch march;

    // Volumes holding uniform radiance `radiance` (per channel): intensity over a cell's
    // cross-section, all in the SH's band 0.
    FogRig(rhi::Device& d, glm::vec3 radiance) : device(d), march(d) {
        using namespace rhi;
        depth = d.createTexture({TextureKind::Tex2D, Format::D32F, kWidth, kHeight, 1, 1,
                                 kTextureDepthTarget | kTextureSampled, "fog test depth"});
        shadow = d.createTexture({TextureKind::Tex2D, Format::D32F, 8, 8, 1, 1,
                                  kTextureDepthTarget | kTextureSampled, "fog test shadow"});
        target =
            d.createTexture({TextureKind::Tex2D, Format::RGBA16F, kWidth, kHeight, 1, 1,
                             kTextureColorTarget | kTextureSampled | kTextureTransfer, "fog test target"});
        const float band0 = 0.282094792f * 4.0f * std::numbers::pi_v<float> * kCell * kCell;
        for (int ch = 0; ch < 3; ++ch) {
            volumes[size_t(ch)] =
                d.createTexture({TextureKind::Tex3D, Format::RGBA16F, kCells, kCells, kCells, 1,
                                 kTextureSampled | kTextureTransfer, "fog test volume"});
            std::vector<uint16_t> texels(size_t(kCells) * kCells * kCells * 4, 0);
            for (size_t i = 0; i < texels.size(); i += 4)
                texels[i] = glm::packHalf1x16(radiance[ch] * band0);
            d.uploadTexture(volumes[size_t(ch)], 0, texels.data(), texels.size() * sizeof(uint16_t));
        }
    }
    ~FogRig() {
        device.waitIdle();
        for (rhi::TextureHandle t : {depth, shadow, target, volumes[0], volumes[1], volumes[2]})
            device.destroy(t);
    }

    // One frame: the depth buffer and the shadow map cleared to the given values, then the march.
    Image run(const gi::FogSettings& settings, float depthValue, float shadowValue, glm::vec3 sunRadiance,
              glm::vec3 sunDirection, bool withVolumes, const engine::Bounds& bounds) {
        using namespace rhi;
        CommandList& cmd = device.beginFrame();
        for (const auto& [texture, value] : {std::pair{depth, depthValue}, std::pair{shadow, shadowValue}}) {
            RenderPassDesc pass;
            pass.depth = {texture, 0, LoadOp::Clear, value};
            pass.debugName = "fog test clear";
            cmd.beginRenderPass(pass);
            cmd.endRenderPass();
        }
        gi::FogInputs in;
        in.camera = fogCamera();
        in.gbuffer.depth = depth;
        in.gbuffer.width = kWidth;
        in.gbuffer.height = kHeight;
        in.sun.shadowMap = shadow;
        // The shadow map covers the whole scene from above.
        in.sun.viewProjection = glm::orthoRH_ZO(-200.0f, 200.0f, -200.0f, 200.0f, 0.0f, 400.0f) *
                                glm::lookAt(glm::vec3(0, 200, 0), glm::vec3(0), glm::vec3(0, 0, -1));
        in.sun.direction = glm::normalize(sunDirection);
        in.sun.radiance = sunRadiance;
        in.sun.depthBias = 0.0f;
        const gi::FogCascade cascade{{glm::vec3(-0.5f * kCell * kCells), kCell, kCells}, volumes};
        if (withVolumes) in.cascades = std::span(&cascade, 1);
        in.sceneBounds = bounds;
        march.record(cmd, settings, in, target);
        device.endFrame();
        device.waitIdle();
        return readImage(device, target);
    }
};

gi::FogSettings homogeneous(float density, float g) {
    gi::FogSettings s;
    s.enabled = true;
    s.density = density;
    s.albedo = glm::vec3(0.8f, 0.6f, 0.4f);
    s.anisotropy = g;
    s.resolutionDivisor = 1;
    s.steps = 7;
    return s;
}

engine::Bounds box(float half) {
    engine::Bounds b;
    b.add(glm::vec3(-half));
    b.add(glm::vec3(half));
    return b;
}

// |got - want| within fp16's rounding of the larger of the two (and a floor for values near 0).
void checkNear(float got, float want, const char* what, uint32_t x, uint32_t y) {
    const float tolerance = 2e-3f * std::max(std::fabs(want), 1.0f) + 1e-4f;
    if (std::fabs(got - want) > tolerance)
        FAIL_CHECK(what << " at (" << x << ", " << y << "): " << got << ", closed form " << want);
}

} // namespace

TEST_CASE(
    "gi: fog in uniform radiance scatters albedo x L x (1 - exp(-sigma d)) and lets exp(-sigma d) through") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const glm::vec3 radiance(1.0f, 0.5f, 0.25f);
            FogRig rig(*device, radiance);
            const engine::CameraMatrices camera = fogCamera();
            // Anisotropy does not change what a uniform field scatters (band 1 is empty).
            for (const float g : {0.0f, 0.6f}) {
                const gi::FogSettings fog = homogeneous(0.05f, g);
                const float depthValue = 0.995f; // rays of about 50 to 70 m
                const Image m =
                    rig.run(fog, depthValue, 1.0f, glm::vec3(0.0f), glm::vec3(0, -1, 0), true, box(90.0f));
                for (uint32_t y = 0; y < kHeight; ++y)
                    for (uint32_t x = 0; x < kWidth; ++x) {
                        const float d = pixelRay(camera, x, y, depthValue).length;
                        const float t = std::exp(-fog.density * d);
                        const glm::vec4 v = m.at(x, y);
                        for (int ch = 0; ch < 3; ++ch)
                            checkNear(v[ch], fog.albedo[ch] * radiance[ch] * (1.0f - t), "in-scattered", x,
                                      y);
                        checkNear(v.a, t, "transmittance", x, y);
                    }
            }
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: the sun's single scattering in fog follows the phase function, and its shadow takes it away") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            FogRig rig(*device, glm::vec3(0.0f));
            const engine::CameraMatrices camera = fogCamera();
            const glm::vec3 sun(3.0f, 2.0f, 1.0f);
            // The sun shines toward the camera's right and away from it: each pixel sees another angle.
            const glm::vec3 sunDirection = glm::normalize(glm::vec3(1.0f, -0.3f, -0.5f));
            for (const float g : {0.0f, 0.6f}) {
                const gi::FogSettings fog = homogeneous(0.03f, g);
                // No surface: each ray stops where it leaves the scene's bounds, a box of 40 m around the
                // camera.
                const Image lit = rig.run(fog, 1.0f, 1.0f, sun, sunDirection, false, box(20.0f));
                for (uint32_t y = 0; y < kHeight; ++y)
                    for (uint32_t x = 0; x < kWidth; ++x) {
                        const PixelRay r = pixelRay(camera, x, y, 0.5f);
                        const glm::vec3 inv = 1.0f / r.direction;
                        const glm::vec3 far = glm::max(glm::vec3(-20.0f) * inv, glm::vec3(20.0f) * inv);
                        const float d = std::min({far.x, far.y, far.z});
                        const float t = std::exp(-fog.density * d);
                        const float phase = henyeyGreenstein(glm::dot(sunDirection, -r.direction), g);
                        const glm::vec4 v = lit.at(x, y);
                        for (int ch = 0; ch < 3; ++ch)
                            checkNear(v[ch], fog.albedo[ch] * sun[ch] * phase * (1.0f - t),
                                      "sun in-scattered", x, y);
                        checkNear(v.a, t, "transmittance", x, y);
                    }
            }
            // A shadow map at depth 0 shadows every point: no shafts, the same transmittance.
            const gi::FogSettings fog = homogeneous(0.03f, 0.3f);
            const Image dark = rig.run(fog, 1.0f, 0.0f, sun, sunDirection, false, box(20.0f));
            for (uint32_t y = 0; y < kHeight; ++y)
                for (uint32_t x = 0; x < kWidth; ++x) {
                    const glm::vec4 v = dark.at(x, y);
                    CHECK(v.r + v.g + v.b == 0.0f);
                    CHECK(v.a < 1.0f);
                }
            device.expectSilent();
        }
    }
}

namespace {

// The Cornell box with the sun through its opening, at 160x120, with `settings` on top.
CornellFrame foggyCornell(rhi::Device& device, const std::vector<std::string>& settings) {
    std::vector<std::string> all{"gi.enabled=true", "render.ssao=false", "gi.cell_size=0.34",
                                 "gi.cascades=1"};
    all.insert(all.end(), settings.begin(), settings.end());
    return renderCornell(device, all, std::nullopt, 160, 120, 1);
}

} // namespace

TEST_CASE("gi: fog of zero density leaves the frame bit for bit; the fog view shows its light alone") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame off = foggyCornell(*device, {});
            const CornellFrame none = foggyCornell(*device, {"fog.enabled=true", "fog.density=0"});
            REQUIRE(off.hdr.texels.size() == none.hdr.texels.size());
            size_t differing = 0;
            for (size_t i = 0; i < off.hdr.texels.size(); ++i)
                if (off.hdr.texels[i] != none.hdr.texels[i]) ++differing;
            CHECK(differing == 0);
            // Thick fog: the frame's light is the fog's, and the fog view holds some of it.
            const CornellFrame thick = foggyCornell(*device, {"fog.enabled=true", "fog.density=0.3"});
            const CornellFrame view =
                foggyCornell(*device, {"fog.enabled=true", "fog.density=0.3", "render.debug_view=fog"});
            const double fogLight = meanLuminance(view.hdr);
            MESSAGE(backend.name << ": mean luminance without fog " << meanLuminance(off.hdr) << ", in fog "
                                 << meanLuminance(thick.hdr) << ", of the fog alone " << fogLight);
            CHECK(fogLight > 0.0);
            CHECK(fogLight < meanLuminance(thick.hdr));
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: GL and Vulkan compute the same fog") {
    const std::vector<std::string> settings{"fog.enabled=true", "fog.density=0.3", "render.debug_view=fog"};
    CornellFrame gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = foggyCornell(*device, settings);
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = foggyCornell(*device, settings);
        device.expectSilent();
    }
    checkBackendsAgree(gl.hdr, vk.hdr, "fog");
}
