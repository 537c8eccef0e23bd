// Spot lights with their own RSM (gi.light_rsms) on each backend: the VPLs of a light at a point
// shift toward it along their own direction, several lights in one injection; the RSM's VPLs carry the flux
// the cone delivers, times the albedo (the units the sun's VPLs have); in the Cornell box a spot on the red
// wall bleeds red onto the floor through its RSM and does not when it is analytic (white light); the lighting
// pass lights an RSM spot per pixel and not an analytic one; GL and Vulkan agree. Point lights with a
// cube RSM (gi.point_light_rsms): the six faces' VPLs carry all the flux the light sends, times the
// albedo; by the red wall one bleeds red and the lighting pass lights it per pixel; GL and Vulkan agree.
#include "../render/CornellFrame.h"
#include "../render/SpecularLobe.h"
#include "../support/TestDevice.h"
#include "GpuVpls.h"

#include "engine/render/GpuScene.h"
#include "engine/render/SpecularAlbedo.h"
#include "engine/render/SpecularAlbedoTexture.h"
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"
#include "gi/LpvInjection.h"
#include "gi/LpvReference.h"
#include "gi/LpvVolumes.h"
#include "gi/SpotLightRsms.h"

#include <doctest/doctest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

engine::Light spotLight(glm::vec3 position, glm::vec3 target, float inner, float outer, float intensity) {
    engine::Light l;
    l.name = "spot";
    l.type = engine::LightType::Spot;
    l.position = position;
    l.direction = glm::normalize(target - position);
    l.innerConeAngle = inner;
    l.outerConeAngle = outer;
    l.intensity = intensity;
    return l;
}

// The Cornell box without its sun, and a white spot light from the right half of the room onto
// the lower red wall; the floor by the wall is inside its cone too.
engine::Scene spotOnRedWall() {
    engine::Scene scene = engine::buildCornellBox();
    scene.lights.push_back(spotLight({0.5f, 3.0f, 2.0f}, {-2.75f, 1.0f, 1.5f}, 0.35f, 0.5f, 60.0f));
    return scene;
}

const auto kNoSun = [](engine::Renderer& r) { r.sun().radiance = glm::vec3(0.0f); };

// 32 cells of 0.17 m span the box's interior (as the sun's colour-bleeding test).
std::vector<std::string> indirectView(std::initializer_list<const char*> extra = {}) {
    std::vector<std::string> v = {"gi.enabled=true", "render.debug_view=indirect", "gi.cell_size=0.17",
                                  "gi.iterations=16", "render.ssao=false"};
    v.insert(v.end(), extra.begin(), extra.end());
    return v;
}

float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// What engine/shaders/lighting.frag gives a surface at `p` with normal `n` from `l` (no range).
glm::vec3 spotIrradiance(const engine::Light& l, glm::vec3 p, glm::vec3 n) {
    const glm::vec3 toLight = l.position - p;
    const float d2 = glm::dot(toLight, toLight);
    const glm::vec3 dir = toLight / std::sqrt(d2);
    const float cone =
        smoothstep(std::cos(l.outerConeAngle), std::cos(l.innerConeAngle), glm::dot(-dir, l.direction));
    return l.color * l.intensity * cone / d2 * std::max(glm::dot(n, dir), 0.0f);
}

const glm::vec3 kFloorByRedWall{-2.2f, 0.0f, 2.0f};

engine::Light pointLight(glm::vec3 position, float intensity) {
    engine::Light l;
    l.name = "point";
    l.type = engine::LightType::Point;
    l.position = position;
    l.intensity = intensity;
    return l;
}

// What engine/shaders/lighting.frag gives a surface at `p` with normal `n` from a point light (no
// range).
glm::vec3 pointIrradiance(const engine::Light& l, glm::vec3 p, glm::vec3 n) {
    const glm::vec3 toLight = l.position - p;
    const float d2 = glm::dot(toLight, toLight);
    return l.color * l.intensity / d2 * std::max(glm::dot(n, toLight / std::sqrt(d2)), 0.0f);
}

// The Cornell box without its sun, and a white point light in the room's red half, nearer the red
// wall than the others.
engine::Scene pointByRedWall() {
    engine::Scene scene = engine::buildCornellBox();
    scene.lights.push_back(pointLight({-1.6f, 2.2f, 1.5f}, 12.0f));
    return scene;
}

// The integral over the sphere of directions from `light`, inside the box (min, max), of the
// share of the light the box's diffuse walls keep at the angle each direction meets them:
// (1 - F0) (1 - the Schlick mean), F0 4% (engine/render/SpecularAlbedo.h). Midpoint rule in
// cos(theta) and phi.
float keptOverSphere(glm::vec3 light, glm::vec3 min, glm::vec3 max) {
    const engine::SpecularAlbedoTable& table = engine::specularAlbedoTable();
    const int steps = 512;
    double sum = 0.0;
    for (int t = 0; t < steps; ++t) {
        const float z = -1.0f + 2.0f * (float(t) + 0.5f) / float(steps), r = std::sqrt(1.0f - z * z);
        for (int p = 0; p < 2 * steps; ++p) {
            const float phi = 3.14159265f * (float(p) + 0.5f) / float(steps);
            const glm::vec3 d(r * std::cos(phi), r * std::sin(phi), z);
            // The wall hit first: the axis whose bounding plane the ray reaches soonest.
            float nearest = 1e30f, cosWall = 0.0f;
            for (int a = 0; a < 3; ++a) {
                if (std::fabs(d[a]) < 1e-6f) continue;
                const float hit = ((d[a] > 0.0f ? max[a] : min[a]) - light[a]) / d[a];
                if (hit < nearest) {
                    nearest = hit;
                    cosWall = std::fabs(d[a]);
                }
            }
            sum += 0.96 * (1.0 - table.schlickMeanAt(cosWall));
        }
    }
    return float(sum * 4.0 * 3.14159265 / (double(steps) * 2 * steps));
}

// What the VPLs of a light's RSM(s) carry.
struct VplTotals {
    glm::vec3 flux{0.0f};
    uint32_t total = 0, lit = 0, facingLight = 0;
    uint32_t blocks = 0, blocksLit = 0; // RSM blocks (kVplsPerCluster slots each), those with a lit VPL
    void add(const std::vector<GpuVpl>& vpls, glm::vec3 lightPosition) {
        for (size_t b = 0; b + gi::kVplsPerCluster <= vpls.size(); b += gi::kVplsPerCluster) {
            ++blocks;
            bool any = false;
            for (uint32_t k = 0; k < gi::kVplsPerCluster; ++k)
                any = any || vpls[b + k].position.w > 0.0f;
            blocksLit += any ? 1 : 0;
        }
        for (const GpuVpl& v : vpls) {
            ++total;
            if (v.position.w <= 0.0f) continue;
            ++lit;
            flux += glm::vec3(v.flux);
            // Every lit VPL faces the light (the RSM turns two-sided surfaces toward it).
            if (glm::dot(glm::vec3(v.normal), lightPosition - glm::vec3(v.position)) > 0.0f) ++facingLight;
        }
    }
};

// The direct light the lighting pass gives pixel (x, y) of `scene` under `settings`: the final
// image less the indirect light's diffuse and glossy terms. Each view is rounded to RGBA16F on its
// own, so the difference carries up to 1e-3 of the final value, which `total` receives.
glm::vec3 directLight(rhi::Device& device, const engine::Scene& scene, std::vector<std::string> settings,
                      uint32_t x, uint32_t y, glm::vec3* total = nullptr) {
    const CornellFrame final = renderSceneFrame(device, scene, settings, kNoSun);
    settings.push_back("render.debug_view=indirect");
    const CornellFrame indirect = renderSceneFrame(device, scene, settings, kNoSun);
    settings.back() = "render.debug_view=glossy";
    const CornellFrame glossy = renderSceneFrame(device, scene, settings, kNoSun);
    if (total) *total = glm::vec3(final.hdr.at(x, y));
    return glm::vec3(final.hdr.at(x, y) - indirect.hdr.at(x, y) - glossy.hdr.at(x, y));
}

// The indirect light of `scene` under `settings` on gl-egl and on Vulkan: as for the sun's, within
// 1% of the brightest value on 99% of the pixels.
void checkApisAgree(const engine::Scene& scene, const std::vector<std::string>& settings, const char* what) {
    const FramesOnBothApis f = renderOnGlAndVulkan(scene, settings, kNoSun);
    checkBackendsAgree(f.gl.hdr, f.vk.hdr, what);
}

} // namespace

TEST_CASE("gi: VPLs of a light at a point shift along the line from it; lights share one injection") {
    const gi::VolumeGrid grid{{0.0f, 0.0f, 0.0f}, 0.5f, 16};
    const glm::vec3 sunDirection = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    const glm::vec3 spotPosition{4.1f, 6.1f, 4.1f};
    const std::vector<gi::Vpl> sunVpls = {{{3.3f, 1.2f, 5.1f}, {0, 1, 0}, {1.0f, 0.5f, 0.2f}}};
    // Near cell borders, where the shift toward the light decides the cell.
    const std::vector<gi::Vpl> spotVpls = {{{2.45f, 2.2f, 2.45f}, {0, 1, 0}, {0.2f, 0.4f, 1.0f}},
                                           {{6.05f, 2.2f, 6.05f}, {0, 1, 0}, {0.5f, 0.5f, 0.5f}},
                                           {{1.1f, 4.4f, 4.2f}, {1, 0, 0}, {0.9f, 0.1f, 0.3f}}};
    gi::ShVolume reference(grid.size);
    gi::injectReference(reference, grid, sunVpls, sunDirection);
    uint32_t moved = 0; // VPLs whose cell a constant direction (the spot's axis) would get wrong
    for (const gi::Vpl& v : spotVpls) {
        const glm::vec3 travel = glm::normalize(v.position - spotPosition);
        gi::injectReference(reference, grid, {v}, travel);
        glm::ivec3 own, constant;
        REQUIRE(gi::injectionCell(grid, v, travel, own));
        if (!gi::injectionCell(grid, v, {0, -1, 0}, constant) || own != constant) ++moved;
    }
    REQUIRE(moved >= 2);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            gi::LpvSettings s;
            s.gridSize = grid.size;
            s.shFormat = gi::ShFormat::Rgba32f; // float injection volume
            const rhi::BufferHandle sun = uploadVpls(*device, sunVpls), spot = uploadVpls(*device, spotVpls);
            float worst = 0.0f, peak = 0.0f;
            {
                gi::LpvVolumes volumes(*device, s);
                gi::LpvInjection injection(*device, s);
                const gi::VplSource sources[] = {
                    {sun, uint32_t(sunVpls.size()), glm::vec4(sunDirection, 0.0f)},
                    {spot, uint32_t(spotVpls.size()), glm::vec4(spotPosition, 1.0f)}};
                rhi::CommandList& cmd = device->beginFrame();
                injection.record(cmd, volumes, sources, grid, 1.0f);
                device->endFrame();
                device->waitIdle();
                for (uint32_t ch = 0; ch < 3; ++ch) {
                    const Image got = readImage(*device, volumes.injected()[ch]);
                    for (uint32_t z = 0; z < grid.size; ++z)
                        for (uint32_t y = 0; y < grid.size; ++y)
                            for (uint32_t x = 0; x < grid.size; ++x) {
                                const gi::ShCell& want = reference.at(x, y, z);
                                const glm::vec4 w = ch == 0 ? want.r : ch == 1 ? want.g : want.b;
                                for (int k = 0; k < 4; ++k) {
                                    worst = std::max(worst, std::fabs(got.at(x, y, z)[k] - w[k]));
                                    peak = std::max(peak, std::fabs(w[k]));
                                }
                            }
                }
            }
            device->destroy(sun);
            device->destroy(spot);
            MESSAGE(backend.name << ": injection of a sun and a point-source VPL set, largest difference "
                                 << worst << " (peak " << peak << ")");
            REQUIRE(peak > 0.0f);
            CHECK(worst <= 1e-5f * peak);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: a spot light's RSM reflects the flux its cone delivers, times the albedo") {
    // Straight down from under the ceiling: the whole cone lands on the floor and the box tops
    // (albedo 0.73 all, level: light at angle theta off the axis arrives at theta off their normal),
    // none on the coloured walls. Reflected flux = albedo x I x the integral over the cone of its
    // smoothstep falloff times the share the diffuse base keeps, (1 - F0) (1 - the Schlick mean).
    engine::Scene box = engine::buildCornellBox();
    const engine::Light spot = spotLight({0.0f, 4.5f, 0.0f}, {0.0f, 0.0f, 0.0f}, 0.3f, 0.5f, 10.0f);
    const std::vector<engine::Light> lights = {spot};
    const engine::SpecularAlbedoTable& table = engine::specularAlbedoTable();
    double coneIntegral = 0.0, keptIntegral = 0.0;
    const int steps = 4000;
    for (int i = 0; i < steps; ++i) {
        const float theta = (float(i) + 0.5f) / float(steps) * spot.outerConeAngle;
        const double w =
            2.0 * 3.14159265 * std::sin(theta) * (spot.outerConeAngle / steps) *
            smoothstep(std::cos(spot.outerConeAngle), std::cos(spot.innerConeAngle), std::cos(theta));
        coneIntegral += w;
        keptIntegral += w * 0.96 * (1.0 - table.schlickMeanAt(std::cos(theta)));
    }
    // The falloff's integral has a closed form: a check of the sum above.
    REQUIRE(coneIntegral ==
            doctest::Approx(2.0 * 3.14159265 *
                            (1.0 - 0.5 * (std::cos(spot.innerConeAngle) + std::cos(spot.outerConeAngle))))
                .epsilon(1e-4));
    const float expected = 0.73f * spot.intensity * float(keptIntegral);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            gi::LpvSettings s; // RSM 256, 4096 VPLs for the sun: 1024 for a spot
            s.lightRsms = 1;
            std::vector<GpuVpl> vpls(gi::spotLightVplSlots(s));
            {
                engine::GpuScene scene(*device, box);
                const engine::SpecularAlbedoTexture specularAlbedo(*device);
                gi::SpotLightRsms rsms(*device, s);
                rsms.select(lights, gi::VolumeGrid{{-8.0f, -8.0f, -8.0f}, 0.5f, 32});
                REQUIRE(rsms.selection().size() == 1);
                rhi::CommandList& cmd = device->beginFrame();
                rsms.record(cmd, scene, specularAlbedo.texture(), lights);
                device->endFrame();
                device->waitIdle();
                REQUIRE(rsms.sources().size() == 1);
                CHECK(rsms.sources()[0].light == glm::vec4(spot.position, 1.0f));
                device->readBuffer(rsms.sources()[0].vpls, 0, vpls.data(), vpls.size() * sizeof(GpuVpl));
            }
            VplTotals sum;
            sum.add(vpls, spot.position);
            const glm::vec3 flux = sum.flux;
            MESSAGE(backend.name << ": " << sum.lit << " lit VPLs carry " << flux.r << ", " << flux.g << ", "
                                 << flux.b << " W; the cone delivers x albedo x the diffuse share "
                                 << expected << " W");
            CHECK(sum.lit > vpls.size() / 2);
            CHECK(sum.facingLight == sum.lit);
            for (int c = 0; c < 3; ++c)
                // Measured 0.4% under (0.05% before the share): the boxes' sides catch part of the
                // cone at steeper angles than the level surfaces this formula assumes, and lose more.
                CHECK(flux[c] == doctest::Approx(expected).epsilon(0.01));
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: a spot light with its own RSM bleeds the colour it hits; an analytic one does not") {
    const engine::Scene scene = spotOnRedWall();
    const engine::Light& spot = scene.lights.back();
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame rsm = renderSceneFrame(*device, scene, indirectView(), kNoSun);
            const CornellFrame analytic =
                renderSceneFrame(*device, scene, indirectView({"gi.light_rsms=0"}), kNoSun);
            uint32_t x = 0, y = 0;
            REQUIRE(rsm.pixelOf(kFloorByRedWall, x, y));
            const glm::vec4 bounce = rsm.hdr.at(x, y), white = analytic.hdr.at(x, y);
            MESSAGE(backend.name << ": indirect on the floor by the red wall, spot with an RSM "
                                 << describe(bounce) << ", analytic spot " << describe(white));
            // Through its RSM the light reflected by the red wall reaches the floor red.
            CHECK(bounce.r > 1.5f * bounce.g);
            CHECK(bounce.r > 1.5f * bounce.b);
            // Analytic, the volume holds the spot's own white light there, and no bounce.
            CHECK(luminance(white) > 0.0f);
            CHECK(white.r == doctest::Approx(white.g).epsilon(0.02));
            CHECK(white.r == doctest::Approx(white.b).epsilon(0.02));

            // The lighting pass lights the RSM spot per pixel (the volume holds only its bounce),
            // as lighting.frag's formula says, and adds nothing for the analytic one.
            const std::vector<std::string> lit = {"gi.enabled=true", "gi.cell_size=0.17",
                                                  "render.ssao=false"};
            const glm::vec3 direct = directLight(*device, scene, lit, x, y);
            // Lambert under the GGX lobe of the fully rough white paint (SpecularLobe.h).
            const glm::vec3 toEye = rsm.camera.position - kFloorByRedWall,
                            toSpot = spot.position - kFloorByRedWall;
            const float reflectance = 0.73f / 3.14159265f * diffuseShare(toEye, toSpot) +
                                      specularLobe({0, 1, 0}, toEye, toSpot, 1.0f);
            const glm::vec3 want = reflectance * spotIrradiance(spot, kFloorByRedWall, {0, 1, 0});
            MESSAGE(backend.name << ": direct light of the RSM spot " << describe(glm::vec4(direct, 1))
                                 << ", lighting.frag's formula " << describe(glm::vec4(want, 1)));
            REQUIRE(want.g > 0.1f);
            CHECK(direct.g == doctest::Approx(want.g).epsilon(0.02));
            std::vector<std::string> analyticLit = lit;
            analyticLit.push_back("gi.light_rsms=0");
            glm::vec3 total(0.0f);
            const glm::vec3 none = directLight(*device, scene, analyticLit, x, y, &total);
            MESSAGE(backend.name << ": direct light of the analytic spot " << describe(glm::vec4(none, 1))
                                 << " in a pixel of " << describe(glm::vec4(total, 1)));
            CHECK(std::fabs(none.g) <= 1e-3f * total.g);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: GL and Vulkan compute the same spot light bounce") {
    checkApisAgree(spotOnRedWall(), indirectView(), "spot light bounce");
}

TEST_CASE("gi: a point light's cube RSM reflects all the flux it sends, times the albedo") {
    // Inside a closed grey room (albedo 0.5 everywhere), every direction from the light meets a
    // wall: the six faces' VPLs carry albedo x I x the integral over the sphere of the share the
    // wall's diffuse base keeps of light arriving at its angle, (1 - F0) (1 - the Schlick mean).
    const glm::vec3 roomMin{-2.0f, -1.5f, -2.5f}, roomMax{2.0f, 2.5f, 1.5f};
    engine::Scene room;
    room.name = "closed room";
    engine::Material grey;
    grey.name = "grey";
    grey.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    room.materials.push_back(grey);
    engine::MeshBuilder builder(room);
    builder.begin("walls", 0);
    builder.box(roomMin, roomMax, true);
    builder.finish();
    room.updateBounds();
    const engine::Light point = pointLight({0.3f, 0.2f, -0.4f}, 10.0f);
    const std::vector<engine::Light> lights = {point};
    const float expected = 0.5f * point.intensity * keptOverSphere(point.position, roomMin, roomMax);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            gi::LpvSettings s; // RSM 256 per face, 1024 VPLs per face
            s.lightRsms = 0;
            s.pointLightRsms = 1;
            std::vector<std::vector<GpuVpl>> faces(gi::kCubeFaces,
                                                   std::vector<GpuVpl>(gi::spotLightVplSlots(s)));
            {
                engine::GpuScene scene(*device, room);
                const engine::SpecularAlbedoTexture specularAlbedo(*device);
                gi::SpotLightRsms rsms(*device, s);
                rsms.select(lights, gi::VolumeGrid{{-8.0f, -8.0f, -8.0f}, 0.5f, 32});
                REQUIRE(rsms.selection().size() == 1);
                REQUIRE(rsms.rsmCount() == gi::kCubeFaces);
                CHECK(rsms.selected(0));
                rhi::CommandList& cmd = device->beginFrame();
                rsms.record(cmd, scene, specularAlbedo.texture(), lights);
                device->endFrame();
                device->waitIdle();
                REQUIRE(rsms.sources().size() == gi::kCubeFaces);
                for (uint32_t f = 0; f < gi::kCubeFaces; ++f) {
                    CHECK(rsms.sources()[f].light == glm::vec4(point.position, 1.0f));
                    device->readBuffer(rsms.sources()[f].vpls, 0, faces[f].data(),
                                       faces[f].size() * sizeof(GpuVpl));
                }
            }
            VplTotals sum;
            for (const auto& vpls : faces)
                sum.add(vpls, point.position);
            const glm::vec3 flux = sum.flux;
            MESSAGE(backend.name << ": " << sum.lit << " of " << sum.total << " VPL slots lit ("
                                 << sum.blocksLit << " of " << sum.blocks << " blocks), carrying " << flux.r
                                 << ", " << flux.g << ", " << flux.b
                                 << " W; albedo x I x the diffuse share over the sphere = " << expected
                                 << " W");
            CHECK(sum.blocksLit == sum.blocks); // walls all around: every block of every face sees one
            CHECK(sum.facingLight == sum.lit);
            for (int c = 0; c < 3; ++c)
                CHECK(flux[c] == doctest::Approx(expected).epsilon(0.005)); // measured 0.03%
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: a point light with its own cube RSM bleeds the colour it hits; an analytic one does not") {
    const engine::Scene scene = pointByRedWall();
    const engine::Light& point = scene.lights.back();
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame rsm =
                renderSceneFrame(*device, scene, indirectView({"gi.point_light_rsms=1"}), kNoSun);
            const CornellFrame analytic =
                renderSceneFrame(*device, scene, indirectView({"gi.point_light_rsms=0"}), kNoSun);
            uint32_t x = 0, y = 0;
            REQUIRE(rsm.pixelOf(kFloorByRedWall, x, y));
            const glm::vec4 bounce = rsm.hdr.at(x, y), white = analytic.hdr.at(x, y);
            MESSAGE(backend.name << ": indirect on the floor by the red wall, point light with a cube RSM "
                                 << describe(bounce) << ", analytic point light " << describe(white));
            // The red wall's bounce reaches the floor red (measured 1.44x; the white ceiling's and
            // floor's bounce dilute it more than under the spot, which lights mostly the wall).
            CHECK(bounce.r > 1.3f * bounce.g);
            CHECK(bounce.r > 1.3f * bounce.b);
            CHECK(luminance(white) > 0.0f);
            CHECK(white.r == doctest::Approx(white.g).epsilon(0.02));
            CHECK(white.r == doctest::Approx(white.b).epsilon(0.02));
            // The lighting pass lights it per pixel, as lighting.frag's formula says.
            const glm::vec3 direct = directLight(
                *device, scene,
                {"gi.enabled=true", "gi.cell_size=0.17", "render.ssao=false", "gi.point_light_rsms=1"}, x, y);
            const glm::vec3 toEye = rsm.camera.position - kFloorByRedWall,
                            toPoint = point.position - kFloorByRedWall;
            const float reflectance = 0.73f / 3.14159265f * diffuseShare(toEye, toPoint) +
                                      specularLobe({0, 1, 0}, toEye, toPoint, 1.0f);
            const glm::vec3 want = reflectance * pointIrradiance(point, kFloorByRedWall, {0, 1, 0});
            MESSAGE(backend.name << ": direct light of the RSM point light " << describe(glm::vec4(direct, 1))
                                 << ", lighting.frag's formula " << describe(glm::vec4(want, 1)));
            REQUIRE(want.g > 0.1f);
            CHECK(direct.g == doctest::Approx(want.g).epsilon(0.02));
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: GL and Vulkan compute the same point light bounce") {
    checkApisAgree(pointByRedWall(), indirectView({"gi.point_light_rsms=1"}), "point light bounce");
}
