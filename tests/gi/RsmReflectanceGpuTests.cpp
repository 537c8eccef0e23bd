// What a reflective shadow map's texel reflects, on each backend: the diffuse colour (base colour x
// (1 - metallic)) times the share glTF's fresnel_mix leaves the diffuse base of light arriving at the
// sun's angle, (1 - F0) x (1 - the Schlick mean) (engine/render/SpecularAlbedo.h), times the sun's
// irradiance and the texel's area: the light the lit surface shows, summed over every view. Dielectric
// and partly metallic floors (one through its metallic-roughness map), the sun high and grazing; a
// metal reflects nothing.
#include "../support/Image.h"
#include "../support/TestDevice.h"

#include "engine/render/GpuScene.h"
#include "engine/render/SpecularAlbedo.h"
#include "engine/render/SpecularAlbedoTexture.h"
#include "engine/scene/MeshBuilder.h"
#include "gi/ReflectiveShadowMap.h"

#include <doctest/doctest.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

using namespace lpv;
using namespace lpv::test;

namespace {

// A level floor of one material, 10 m across, larger than the RSM's view of the volume below. With
// `metallicMap` (0-255) its metallic factor is scaled by a uniform metallic-roughness map's B.
engine::Scene floorOf(glm::vec3 baseColor, float metallic, float roughness, int metallicMap) {
    engine::Scene scene;
    scene.name = "floor";
    engine::Material m;
    m.name = "floor";
    m.baseColor = glm::vec4(baseColor, 1.0f);
    m.metallic = metallic;
    m.roughness = roughness;
    if (metallicMap >= 0) {
        engine::TextureImage map;
        map.name = "metallic-roughness";
        map.width = map.height = 4;
        map.srgb = false;
        for (int i = 0; i < 16; ++i)
            map.rgba.insert(map.rgba.end(), {0, 255, uint8_t(metallicMap), 255});
        scene.textures.push_back(std::move(map));
        m.metallicRoughnessTexture = 0;
    }
    scene.materials.push_back(m);
    engine::MeshBuilder builder(scene);
    builder.begin("floor", 0);
    builder.quad({-5.0f, 0.0f, 5.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -10.0f}); // faces +y
    builder.finish();
    scene.updateBounds();
    return scene;
}

struct FloorCase {
    glm::vec3 baseColor;
    float metallic, roughness;
    float sunAngle;       // from the floor's normal (radians)
    int metallicMap = -1; // the metallic-roughness map's B (none: -1)
};

} // namespace

TEST_CASE("gi: an RSM texel reflects the diffuse share glTF's fresnel mix leaves its surface") {
    const FloorCase cases[] = {
        {{0.8f, 0.8f, 0.8f}, 0.0f, 0.3f, 1.047f},     // smooth dielectric, the sun 60 degrees down
        {{0.9f, 0.5f, 0.2f}, 0.5f, 0.6f, 0.436f},     // partly metallic, the sun high (25 degrees)
        {{0.7f, 0.7f, 0.7f}, 0.0f, 1.0f, 1.396f},     // rough dielectric, grazing sun (80 degrees)
        {{0.9f, 0.6f, 0.3f}, 1.0f, 0.4f, 0.7f},       // a metal: no diffuse base at all
        {{0.9f, 0.5f, 0.2f}, 1.0f, 0.5f, 0.6f, 128}}; // a metal whose map makes it half metallic
    const glm::vec3 sunIrradiance{2.0f, 1.5f, 1.0f};
    const gi::VolumeGrid grid{{-4.0f, -4.0f, -4.0f}, 0.25f, 32};
    const engine::SpecularAlbedoTable& table = engine::specularAlbedoTable();
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const engine::SpecularAlbedoTexture specularAlbedo(*device);
            for (const FloorCase& c : cases) {
                const glm::vec3 sun{std::sin(c.sunAngle), -std::cos(c.sunAngle), 0.0f}; // travels
                const float cosLight = std::cos(c.sunAngle);
                const float metallic =
                    c.metallic * (c.metallicMap >= 0 ? float(c.metallicMap) / 255.0f : 1.0f);
                const glm::vec3 f0 = glm::mix(glm::vec3(0.04f), c.baseColor, metallic);
                const glm::vec3 diffuse = c.baseColor * (1.0f - metallic);
                const glm::vec3 kept = (1.0f - f0) * (1.0f - table.schlickMeanAt(cosLight));
                Image flux, normal;
                float texelArea = 0.0f;
                {
                    const engine::GpuScene scene(
                        *device, floorOf(c.baseColor, c.metallic, c.roughness, c.metallicMap));
                    gi::ReflectiveShadowMap rsm(*device, 128);
                    rsm.fit(grid, sun);
                    rhi::CommandList& cmd = device->beginFrame();
                    rsm.record(cmd, scene, specularAlbedo.texture(), sun, sunIrradiance);
                    device->endFrame();
                    device->waitIdle();
                    flux = readImage(*device, rsm.flux());
                    normal = readImage(*device, rsm.normal());
                    texelArea = rsm.texelArea();
                }
                const glm::vec3 expected = diffuse * kept * sunIrradiance * texelArea;
                const glm::vec3 albedoAlone = diffuse * sunIrradiance * texelArea; // without the share
                uint32_t floorTexels = 0;
                float worst = 0.0f, brightest = 0.0f, nearestAlbedoAlone = 1e30f;
                for (size_t i = 0; i < flux.texels.size(); ++i) {
                    if (normal.texels[i].w < 0.5f) continue; // cleared: no surface in this texel
                    ++floorTexels;
                    for (int ch = 0; ch < 3; ++ch) {
                        brightest = std::max(brightest, flux.texels[i][ch]);
                        if (expected[ch] <= 0.0f) continue;
                        const float got = flux.texels[i][ch];
                        worst = std::max(worst, std::fabs(got - expected[ch]) / expected[ch]);
                        nearestAlbedoAlone =
                            std::min(nearestAlbedoAlone, std::fabs(got - albedoAlone[ch]) / albedoAlone[ch]);
                    }
                }
                MESSAGE(backend.name << ": metallic " << metallic << ", roughness " << c.roughness
                                     << ", cos(sun) " << cosLight << ": " << floorTexels
                                     << " floor texels; the base keeps " << kept.r << ", " << kept.g << ", "
                                     << kept.b << "; largest relative difference " << worst
                                     << ", from the albedo alone at least " << nearestAlbedoAlone);
                REQUIRE(floorTexels > 1000);
                if (metallic >= 1.0f) {
                    CHECK(brightest == 0.0f);
                    continue;
                }
                // Every texel lies further from the albedo alone (the old shader) than the tolerance
                // below, so the test tells the two apart.
                CHECK(nearestAlbedoAlone > 0.035f);
                // RGBA16F rounding of the flux and of the table; the Schlick mean alone is 0.5% at
                // the 60-degree sun, so a table without it fails too.
                CHECK(worst <= 0.002f);
            }
            device.expectSilent();
        }
    }
}

// Two faces back to back in one plane (a slab laid flat on a floor, its underside on the floor's
// top): the light sees the face turned toward it, whichever is drawn first, so its texels carry
// that face's albedo (gi/shaders/rsm_light_facing.glsl), in the sun's orthographic RSM and a spot
// light's perspective one. The face turned away is drawn first: with equal depths the depth test
// would otherwise keep it.
TEST_CASE("gi: an RSM keeps the face turned to the light where two faces lie back to back") {
    engine::Scene scene;
    scene.name = "back to back";
    scene.materials = {{"red underside", {0.8f, 0.1f, 0.1f, 1.0f}},
                       {"white floor", {0.8f, 0.8f, 0.8f, 1.0f}}};
    engine::MeshBuilder builder(scene);
    builder.begin("underside", 0);
    builder.quad({-4.0f, 0.0f, -4.0f}, {8.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 8.0f}, 3, 5); // faces -y
    builder.finish();
    builder.begin("floor", 1);
    builder.quad({-5.0f, 0.0f, 5.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -10.0f}); // faces +y
    builder.finish();
    scene.updateBounds();
    const gi::VolumeGrid grid{{-4.0f, -4.0f, -4.0f}, 0.25f, 32};
    const glm::vec3 sun = glm::normalize(glm::vec3(0.35f, -1.0f, 0.2f)); // travels
    engine::Light spot;
    spot.type = engine::LightType::Spot;
    spot.position = {0.7f, 4.0f, -0.4f};
    spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.1f));
    spot.intensity = 50.0f;
    spot.outerConeAngle = 0.6f;
    for (const auto& backend : selectedBackends()) {
        for (const gi::RsmLight light : {gi::RsmLight::Sun, gi::RsmLight::Spot}) {
            const char* lightName = light == gi::RsmLight::Sun ? "sun" : "spot";
            SUBCASE((backend.name + " " + lightName).c_str()) {
                TestDevice device(backend);
                const engine::SpecularAlbedoTexture specularAlbedo(*device);
                Image flux, normal;
                {
                    const engine::GpuScene gpuScene(*device, scene);
                    gi::ReflectiveShadowMap rsm(*device, 128, light);
                    rhi::CommandList& cmd = device->beginFrame();
                    if (light == gi::RsmLight::Sun) {
                        rsm.fit(grid, sun);
                        rsm.record(cmd, gpuScene, specularAlbedo.texture(), sun, glm::vec3(1.0f));
                    } else {
                        rsm.recordSpot(cmd, gpuScene, specularAlbedo.texture(), spot, 20.0f);
                    }
                    device->endFrame();
                    device->waitIdle();
                    flux = readImage(*device, rsm.flux());
                    normal = readImage(*device, rsm.normal());
                }
                uint32_t covered = 0, white = 0, upward = 0;
                for (size_t i = 0; i < flux.texels.size(); ++i) {
                    if (normal.texels[i].w < 0.5f || flux.texels[i].r <= 0.0f) continue; // nothing lit
                    ++covered;
                    // The white floor reflects as much green as red; the red underside an eighth.
                    if (flux.texels[i].g > 0.9f * flux.texels[i].r) ++white;
                    // Either face's normal is turned to the light (two-sided), so this checks that
                    // flip, not which face won.
                    if (normal.texels[i].y > 0.99f) ++upward;
                }
                MESSAGE(backend.name << " " << std::string(lightName) << ": " << covered << " lit texels, "
                                     << white << " white, " << upward << " facing up");
                REQUIRE(covered > 1000);
                CHECK(white == covered);
                CHECK(upward == covered);
                device.expectSilent();
            }
        }
    }
}
