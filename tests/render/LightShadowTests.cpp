// Spot and point light shadow maps (render.spot_shadows, render.point_shadows) on each backend: a
// slab under the light shadows the floor under it, the floor beside the shadow and a wall lit
// through other faces of a point light's cube keep their light, and GL and Vulkan agree.
#include "CornellFrame.h"

#include "../support/TestDevice.h"

#include "engine/scene/MeshBuilder.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

// A white floor and a 0.6 m square slab 1 m over it, under a light 3 m over the floor: a spot
// looking straight down, or a point light (with a wall 2 m to its side, which its +x face sees).
// The slab's shadow on the floor is 0.9 m across (3/2 x 0.6), centred under the light. No sun (a
// directional light of intensity 0: without one the renderer keeps its default sun) and no
// ambient, so the light is the only one.
engine::Scene lightOverSlab(engine::LightType type) {
    engine::Scene scene;
    scene.name = "light over a slab";
    scene.materials = {{"white", {0.8f, 0.8f, 0.8f, 1.0f}}};
    engine::MeshBuilder b(scene);
    b.begin("floor", 0);
    b.box({-3.0f, -0.1f, -3.0f}, {3.0f, 0.0f, 3.0f});
    b.finish();
    b.begin("slab", 0);
    b.box({-0.3f, 0.9f, -0.3f}, {0.3f, 1.0f, 0.3f});
    b.finish();
    if (type == engine::LightType::Point) {
        b.begin("wall", 0);
        b.box({2.0f, 0.0f, -3.0f}, {2.1f, 3.0f, 3.0f});
        b.finish();
    }
    engine::Light dark;
    dark.type = engine::LightType::Directional;
    dark.intensity = 0.0f;
    scene.lights.push_back(dark);
    engine::Light light;
    light.name = "light";
    light.type = type;
    light.position = {0.0f, 3.0f, 0.0f};
    light.direction = {0.0f, -1.0f, 0.0f};
    light.intensity = 30.0f;
    light.range = 8.0f;
    light.innerConeAngle = 0.5f;
    light.outerConeAngle = 0.6f;
    scene.lights.push_back(light);
    engine::Camera camera;
    camera.position = {0.0f, 4.0f, 5.0f};
    camera.forward = glm::normalize(glm::vec3(0.0f) - camera.position);
    scene.camera = camera;
    scene.updateBounds();
    return scene;
}

const std::vector<std::string> kOnlyTheLight = {"gi.enabled=false", "render.ssao=false",
                                                "render.ambient=0,0,0"};

std::vector<std::string> with(std::vector<std::string> settings, const std::string& more) {
    settings.push_back(more);
    return settings;
}

float lightAt(const CornellFrame& f, glm::vec3 p) {
    uint32_t x = 0, y = 0;
    REQUIRE_MESSAGE(f.pixelOf(p, x, y), "floor point not visible");
    return luminance(f.hdr.at(x, y));
}

// The light's map shadows the floor under the slab and nothing else (`enable` turns it on); for
// a point light, also not the wall beside it, which other faces of its cube see.
void checkShadowUnderSlab(engine::LightType type, const std::string& enable) {
    const engine::Scene scene = lightOverSlab(type);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame off = renderSceneFrame(
                *device, scene, with(with(kOnlyTheLight, "render.spot_shadows=0"), "render.point_shadows=0"));
            const CornellFrame on = renderSceneFrame(*device, scene, with(kOnlyTheLight, enable));
            // Under the slab's centre, and 0.15 m off it (0.3 m in from the shadow's edge at 0.45 m).
            const glm::vec3 under(0.0f, 0.0f, 0.0f), nearEdge(0.15f, 0.0f, 0.0f);
            const float underOff = lightAt(off, under), underOn = lightAt(on, under);
            const float nearOn = lightAt(on, nearEdge);
            MESSAGE(backend.name << ": under the slab " << underOff << " unshadowed, " << underOn
                                 << " shadowed (" << nearOn << " 0.15 m off centre)");
            REQUIRE(underOff > 0.0f);
            CHECK(underOn < 0.02f * underOff);
            CHECK(nearOn < 0.02f * underOff);
            // Lit points the map must leave as they are (no acne, no light lost where nothing
            // stands in the way): the floor 0.3 m out from the shadow's edge (inside a spot's
            // full-intensity core: atan(0.75 / 3) = 0.24 rad < 0.5) in four directions, and the
            // slab's own top. For the point light, the wall 2 m to its side: at 2.5 m height in its
            // +x face, and at 1 m, on the edge between its +x and -y faces.
            std::vector<glm::vec3> lit = {{0.75f, 0.0f, 0.0f},
                                          {-0.75f, 0.0f, 0.0f},
                                          {0.0f, 0.0f, 0.75f},
                                          {0.0f, 0.0f, -0.75f},
                                          {0.0f, 1.0f, 0.2f}};
            if (type == engine::LightType::Point) {
                lit.push_back({2.0f, 2.5f, 0.0f});
                lit.push_back({2.0f, 1.0f, 0.3f});
            }
            for (const glm::vec3 p : lit) {
                const float a = lightAt(off, p), b = lightAt(on, p);
                MESSAGE("  lit point (" << p.x << ", " << p.y << ", " << p.z << "): " << a << " -> " << b);
                REQUIRE(a > 0.05f * underOff);
                CHECK(std::fabs(b - a) <= 0.01f * a);
            }
            device.expectSilent();
        }
    }
}

} // namespace

TEST_CASE("render: a spot light's shadow map shadows the floor under a slab and nothing else") {
    checkShadowUnderSlab(engine::LightType::Spot, "render.spot_shadows=1");
}

TEST_CASE("render: a point light's shadow cube shadows the floor under a slab and nothing else") {
    checkShadowUnderSlab(engine::LightType::Point, "render.point_shadows=1");
}

TEST_CASE("render: spot and point light shadows are the same image on GL and Vulkan") {
    for (const engine::LightType type : {engine::LightType::Spot, engine::LightType::Point}) {
        const FramesOnBothApis f = renderOnGlAndVulkan(lightOverSlab(type), kOnlyTheLight);
        // As the Cornell box's comparison: 3 8-bit steps, at most 1% of the pixels (edges) beyond.
        const ImageDifference d = compareImages(f.gl.output, f.vk.output, 3.0f / 255.0f + 1e-4f);
        const std::string name = type == engine::LightType::Spot ? "spot" : "point light";
        MESSAGE(name << ": GL vs Vulkan: max difference " << d.maxAbs << ", " << d.texelsOver << " of "
                     << f.gl.output.texels.size() << " pixels over tolerance");
        CHECK(d.texelsOver <= f.gl.output.texels.size() / 100);
        // And the shadow is there on both (the defaults give the light a map).
        uint32_t x = 0, y = 0;
        REQUIRE(f.gl.pixelOf({0.0f, 0.0f, 0.0f}, x, y));
        CHECK(luminance(f.gl.hdr.at(x, y)) < 1e-3f);
        CHECK(luminance(f.vk.hdr.at(x, y)) < 1e-3f);
    }
}
