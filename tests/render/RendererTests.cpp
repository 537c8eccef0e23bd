// The deferred renderer on each backend: shadows, SSAO, and GL/Vulkan agreement.
#include "CornellFrame.h"

#include "../support/TestDevice.h"

#include "engine/scene/BuiltinScenes.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <cmath>

using namespace lpv;
using namespace lpv::test;

namespace {

// Does the ray from p toward the sun (against `d`) leave through the ceiling opening, and does a
// box stand in its way? Boxes are tested as oriented boxes in their own space.
struct SunRay {
    bool throughOpening = false;
    bool blockedByBox = false;
};

SunRay traceToSun(const engine::Scene& scene, glm::vec3 p, glm::vec3 d) {
    SunRay r;
    const glm::vec3 toSun = -glm::normalize(d);
    const float t = (5.5f - p.y) / toSun.y;
    const glm::vec3 atCeiling = p + t * toSun;
    r.throughOpening = std::fabs(atCeiling.x) < 0.6f && std::fabs(atCeiling.z) < 0.6f;
    for (const engine::Instance& inst : scene.instances) {
        const engine::Mesh& mesh = scene.meshes[inst.mesh];
        if (mesh.name != "short box" && mesh.name != "tall box") continue;
        const glm::mat4 inv = glm::inverse(inst.transform);
        const glm::vec3 o = glm::vec3(inv * glm::vec4(p, 1.0f));
        const glm::vec3 dir = glm::vec3(inv * glm::vec4(toSun, 0.0f));
        float tmin = 0.0f, tmax = 1e9f;
        for (int a = 0; a < 3; ++a) {
            const float inv_d = 1.0f / dir[a];
            float t0 = (mesh.bounds.min[a] - o[a]) * inv_d, t1 = (mesh.bounds.max[a] - o[a]) * inv_d;
            if (t0 > t1) std::swap(t0, t1);
            tmin = std::max(tmin, t0);
            tmax = std::min(tmax, t1);
        }
        if (tmin <= tmax) r.blockedByBox = true;
    }
    return r;
}

} // namespace

TEST_CASE("render: a floor point in a box's shadow is darker than a lit floor point") {
    // This sun sends the beam from the opening over the short box, which shadows part of it.
    const glm::vec3 sun(0.3f, -1.0f, 0.35f);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame f = renderCornell(*device, {"render.ssao=false"}, sun);
            float lit = -1.0f, shadowed = -1.0f;
            for (float z = -2.5f; z <= 2.5f && (lit < 0 || shadowed < 0); z += 0.1f)
                for (float x = -2.5f; x <= 2.5f; x += 0.1f) {
                    const glm::vec3 p(x, 0.0f, z);
                    const SunRay ray = traceToSun(f.scene, p, sun);
                    uint32_t px = 0, py = 0;
                    if (!ray.throughOpening || !f.pixelOf(p, px, py)) continue;
                    // Keep away from shadow edges: the neighbours a pixel away agree.
                    const float l = luminance(f.output.at(px, py));
                    if (!ray.blockedByBox && lit < 0 &&
                        !traceToSun(f.scene, p + glm::vec3(0.15f, 0, 0.15f), sun).blockedByBox &&
                        !traceToSun(f.scene, p - glm::vec3(0.15f, 0, 0.15f), sun).blockedByBox)
                        lit = l;
                    if (ray.blockedByBox && shadowed < 0 &&
                        traceToSun(f.scene, p + glm::vec3(0.15f, 0, 0.15f), sun).blockedByBox &&
                        traceToSun(f.scene, p - glm::vec3(0.15f, 0, 0.15f), sun).blockedByBox)
                        shadowed = l;
                }
            REQUIRE_MESSAGE(lit >= 0.0f, "no visible lit floor point found");
            REQUIRE_MESSAGE(shadowed >= 0.0f, "no visible floor point in a box's shadow found");
            MESSAGE(backend.name << ": lit floor " << lit << ", shadowed floor " << shadowed);
            CHECK(shadowed < 0.5f * lit);
            device.expectSilent();
        }
    }
}

// The sun shadow's offset along the normal was 2 cm whatever the scene's size: a room at a
// thousandth of the scale came out sunlit inside.
TEST_CASE("render: the sun's shadows hold at a thousandth of the scale") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // The share of pixels the shadow view shows in the sun's shadow.
            const auto shadowedShare = [&](float scale) {
                engine::Scene scene = engine::buildCornellBox();
                const glm::mat4 s = glm::scale(glm::mat4(1.0f), glm::vec3(scale));
                for (engine::Instance& instance : scene.instances)
                    instance.transform = s * instance.transform;
                for (engine::Light& light : scene.lights) {
                    light.position *= scale;
                    light.range *= scale;
                }
                REQUIRE(scene.camera);
                scene.camera->position *= scale;
                scene.camera->nearPlane *= scale;
                scene.camera->farPlane *= scale;
                scene.updateBounds();
                const CornellFrame f = renderSceneFrame(
                    *device, scene, {"render.debug_view=shadow", "render.ssao=false"}, {}, 160, 120);
                uint32_t shadowed = 0;
                for (const glm::vec4& t : f.hdr.texels)
                    shadowed += t.x < 0.5f ? 1u : 0u;
                return double(shadowed) / double(f.hdr.texels.size());
            };
            const double full = shadowedShare(1.0f), tiny = shadowedShare(1e-3f);
            MESSAGE(backend.name << ": in the sun's shadow " << full << " of the pixels at full scale, "
                                 << tiny << " at 1e-3");
            CHECK(full > 0.5);
            CHECK(std::fabs(tiny - full) < 0.02);
            device.expectSilent();
        }
    }
}

TEST_CASE("render: SSAO darkens a corner") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame f = renderCornell(*device, {"render.debug_view=ssao"});
            uint32_t cx = 0, cy = 0, ox = 0, oy = 0;
            // Where the floor meets the back wall and the red wall, and open floor near the front.
            REQUIRE(f.pixelOf({-2.6f, 0.0f, -2.6f}, cx, cy));
            REQUIRE(f.pixelOf({0.0f, 0.0f, 2.3f}, ox, oy));
            const float corner = f.hdr.at(cx, cy).x, open = f.hdr.at(ox, oy).x;
            MESSAGE(backend.name << ": ambient occlusion corner " << corner << ", open floor " << open);
            CHECK(open > 0.9f);
            CHECK(corner < open - 0.15f);
            device.expectSilent();
        }
    }
}

// A radius below a pixel's depth step: the sample's own uv paired with the depth of its pixel's
// centre put the surface off itself, and floors and walls seen at a grazing angle read about 0.53.
TEST_CASE("render: a small SSAO radius leaves open floor and walls unoccluded") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame f =
                renderCornell(*device, {"render.debug_view=ssao", "render.ssao_radius=0.01"});
            uint32_t fx = 0, fy = 0, wx = 0, wy = 0;
            REQUIRE(f.pixelOf({0.0f, 0.0f, 2.3f}, fx, fy));  // open floor near the front
            REQUIRE(f.pixelOf({-2.7f, 1.5f, 1.0f}, wx, wy)); // the red wall, seen at a grazing angle
            const float floor = f.hdr.at(fx, fy).x, wall = f.hdr.at(wx, wy).x;
            MESSAGE(backend.name << ": ambient occlusion at radius 0.01: floor " << floor << ", wall "
                                 << wall);
            CHECK(floor > 0.95f);
            CHECK(wall > 0.95f);
            device.expectSilent();
        }
    }
}

TEST_CASE("render: the Cornell box is the same image on GL and Vulkan") {
    CornellFrame gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = renderCornell(*device, {});
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = renderCornell(*device, {});
        device.expectSilent();
    }
    // Tolerance: 3 8-bit steps per channel; at most 1% of the pixels (triangle and shadow edges,
    // where the two rasterizers may cover different samples) beyond it.
    const ImageDifference d = compareImages(gl.output, vk.output, 3.0f / 255.0f + 1e-4f);
    MESSAGE("GL vs Vulkan: max difference " << d.maxAbs << ", " << d.texelsOver << " of "
                                            << gl.output.texels.size() << " pixels over tolerance");
    CHECK(d.texelsOver <= gl.output.texels.size() / 100);
}

// The scene's draws go out as indirect multi-draws, one per set of textures (engine::MultiDraw), or,
// on a device without them, one drawIndexed each, in the same order: the two frames are the same
// image bit for bit, G-buffer, sun shadow, RSMs (through the GI's volumes) and spot and point light
// shadows (the lights hall) included.
TEST_CASE("render: a frame drawn by indirect multi-draws equals the frame drawn a call per draw") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            for (const engine::Scene& scene : {engine::buildAtrium(), engine::buildLightHall()}) {
                CAPTURE(scene.name);
                const std::vector<std::string> settings = {"gi.enabled=true", "render.ssao=false"};
                CornellFrame multi, single;
                {
                    TestDevice device(backend);
                    REQUIRE(device->caps().multiDrawIndirect);
                    multi = renderSceneFrame(*device, scene, settings, {}, 160, 90);
                    device.expectSilent();
                }
                {
                    rhi::DeviceConfig config;
                    config.multiDrawIndirect = false;
                    TestDevice device(backend, config);
                    REQUIRE(!device->caps().multiDrawIndirect);
                    single = renderSceneFrame(*device, scene, settings, {}, 160, 90);
                    device.expectSilent();
                }
                CHECK(meanLuminance(multi.hdr) > 0.0);
                CHECK(compareImages(multi.hdr, single.hdr, 0.0f).texelsOver == 0);
                CHECK(compareImages(multi.albedo, single.albedo, 0.0f).texelsOver == 0);
                REQUIRE(multi.cascadeVolumes.size() == single.cascadeVolumes.size());
                for (size_t c = 0; c < multi.cascadeVolumes.size(); ++c)
                    for (size_t k = 0; k < 3; ++k)
                        CHECK(compareImages(multi.cascadeVolumes[c][k], single.cascadeVolumes[c][k], 0.0f)
                                  .texelsOver == 0);
            }
        }
    }
}
