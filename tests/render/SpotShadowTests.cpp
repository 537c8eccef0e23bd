// Spot light shadow maps (render.spot_shadows) on each backend: a slab in a spot's beam shadows the
// floor under it, the floor beside the shadow keeps its light, and GL and Vulkan agree.
#include "CornellFrame.h"

#include "../support/TestDevice.h"

#include "engine/scene/MeshBuilder.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

using namespace lpv;
using namespace lpv::test;

namespace {

// A white floor, a spot 3 m over it looking straight down, and a 0.6 m square slab 1 m over the
// floor in its beam: the slab's shadow on the floor is 0.9 m across (3/2 x 0.6), centred under
// the light. No sun (a directional light of intensity 0: without one the renderer keeps its
// default sun) and no ambient, so the spot is the only light.
engine::Scene spotOverSlab() {
    engine::Scene scene;
    scene.name = "spot over a slab";
    scene.materials = {{"white", {0.8f, 0.8f, 0.8f, 1.0f}}};
    engine::MeshBuilder b(scene);
    b.begin("floor", 0);
    b.box({-3.0f, -0.1f, -3.0f}, {3.0f, 0.0f, 3.0f});
    b.finish();
    b.begin("slab", 0);
    b.box({-0.3f, 0.9f, -0.3f}, {0.3f, 1.0f, 0.3f});
    b.finish();
    engine::Light dark;
    dark.type = engine::LightType::Directional;
    dark.intensity = 0.0f;
    scene.lights.push_back(dark);
    engine::Light spot;
    spot.name = "spot";
    spot.type = engine::LightType::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = 30.0f;
    spot.range = 8.0f;
    spot.innerConeAngle = 0.5f;
    spot.outerConeAngle = 0.6f;
    scene.lights.push_back(spot);
    engine::Camera camera;
    camera.position = {0.0f, 4.0f, 5.0f};
    camera.forward = glm::normalize(glm::vec3(0.0f) - camera.position);
    scene.camera = camera;
    scene.updateBounds();
    return scene;
}

const std::vector<std::string> kOnlyTheSpot = {"gi.enabled=false", "render.ssao=false",
                                               "render.ambient=0,0,0"};

std::vector<std::string> with(std::vector<std::string> settings, const std::string& more) {
    settings.push_back(more);
    return settings;
}

float floorAt(const CornellFrame& f, glm::vec3 p) {
    uint32_t x = 0, y = 0;
    REQUIRE_MESSAGE(f.pixelOf(p, x, y), "floor point not visible");
    return luminance(f.hdr.at(x, y));
}

} // namespace

TEST_CASE("render: a spot light's shadow map shadows the floor under a slab and nothing else") {
    const engine::Scene scene = spotOverSlab();
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame off =
                renderSceneFrame(*device, scene, with(kOnlyTheSpot, "render.spot_shadows=0"));
            const CornellFrame on =
                renderSceneFrame(*device, scene, with(kOnlyTheSpot, "render.spot_shadows=1"));
            // Under the slab's centre, and 0.15 m off it (0.3 m in from the shadow's edge at 0.45 m);
            // beside the shadow, 0.3 m out from its edge and inside the cone's full-intensity core
            // (atan(0.75 / 3) = 0.24 rad < 0.5), in four directions.
            const glm::vec3 under(0.0f, 0.0f, 0.0f), nearEdge(0.15f, 0.0f, 0.0f);
            const float underOff = floorAt(off, under), underOn = floorAt(on, under);
            const float nearOn = floorAt(on, nearEdge);
            MESSAGE(backend.name << ": under the slab " << underOff << " unshadowed, " << underOn
                                 << " shadowed (" << nearOn << " 0.15 m off centre)");
            REQUIRE(underOff > 0.0f);
            CHECK(underOn < 0.02f * underOff);
            CHECK(nearOn < 0.02f * underOff);
            for (const glm::vec3 beside : {glm::vec3(0.75f, 0.0f, 0.0f), glm::vec3(-0.75f, 0.0f, 0.0f),
                                           glm::vec3(0.0f, 0.0f, 0.75f), glm::vec3(0.0f, 0.0f, -0.75f)}) {
                const float a = floorAt(off, beside), b = floorAt(on, beside);
                MESSAGE("  beside the shadow at (" << beside.x << ", " << beside.z << "): " << a << " -> "
                                                   << b);
                REQUIRE(a > 0.5f * underOff);
                // No acne, no light lost where nothing stands in the way.
                CHECK(std::fabs(b - a) <= 0.01f * a);
            }
            // The slab's own top, lit by the spot and facing it, is not shadowed by itself.
            const float topOff = floorAt(off, {0.0f, 1.0f, 0.2f}), topOn = floorAt(on, {0.0f, 1.0f, 0.2f});
            MESSAGE("  slab top: " << topOff << " -> " << topOn);
            CHECK(std::fabs(topOn - topOff) <= 0.01f * topOff);
            device.expectSilent();
        }
    }
}

TEST_CASE("render: a spot light's shadow is the same image on GL and Vulkan") {
    const FramesOnBothApis f =
        renderOnGlAndVulkan(spotOverSlab(), with(kOnlyTheSpot, "render.spot_shadows=1"));
    // As the Cornell box's comparison: 3 8-bit steps, at most 1% of the pixels (edges) beyond.
    const ImageDifference d = compareImages(f.gl.output, f.vk.output, 3.0f / 255.0f + 1e-4f);
    MESSAGE("GL vs Vulkan: max difference " << d.maxAbs << ", " << d.texelsOver << " of "
                                            << f.gl.output.texels.size() << " pixels over tolerance");
    CHECK(d.texelsOver <= f.gl.output.texels.size() / 100);
    // And the shadow is there on both.
    uint32_t x = 0, y = 0;
    REQUIRE(f.gl.pixelOf({0.0f, 0.0f, 0.0f}, x, y));
    CHECK(luminance(f.gl.hdr.at(x, y)) < 1e-3f);
    CHECK(luminance(f.vk.hdr.at(x, y)) < 1e-3f);
}
