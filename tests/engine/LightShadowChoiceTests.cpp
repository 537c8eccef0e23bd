// Which spot and point lights get a shadow map (engine/render/LightShadows.h), on the null device:
// the choice does not depend on a backend, and the null device counts what the pass draws.
#include "engine/render/LightShadows.h"
#include "engine/scene/MeshBuilder.h"

#include "rhi/Device.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

using namespace lpv;
using namespace lpv::engine;

namespace {

GpuPunctualLight spotRecord(glm::vec3 position, float intensity, float range) {
    GpuPunctualLight l;
    l.positionRange = glm::vec4(position, range);
    l.colorIntensity = glm::vec4(1.0f, 1.0f, 1.0f, intensity);
    l.directionType = glm::vec4(0.0f, -1.0f, 0.0f, 2.0f);
    l.cone = glm::vec4(std::cos(0.6f), std::cos(0.5f), 0.0f, 0.0f);
    return l;
}

struct NullScene {
    std::unique_ptr<rhi::Device> device;
    Scene scene;
    std::unique_ptr<GpuScene> gpu;
    CameraMatrices camera;
};

// Two floor tiles far apart (one under each group of lights below); the camera at the origin
// looking down -z.
NullScene nullScene() {
    NullScene s;
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    s.device = rhi::createDevice(config);
    s.scene.materials = {{"white", {0.8f, 0.8f, 0.8f, 1.0f}}};
    MeshBuilder b(s.scene);
    b.begin("near floor", 0);
    b.box({-4.0f, -0.1f, -14.0f}, {4.0f, 0.0f, -2.0f});
    b.finish();
    b.begin("floor behind the camera", 0);
    b.box({-4.0f, -0.1f, 20.0f}, {4.0f, 0.0f, 30.0f});
    b.finish();
    s.scene.updateBounds();
    s.gpu = std::make_unique<GpuScene>(*s.device, s.scene);
    Camera camera;
    camera.position = {0.0f, 2.0f, 0.0f};
    camera.forward = {0.0f, 0.0f, -1.0f};
    s.camera = cameraMatrices(camera, 16.0f / 9.0f);
    return s;
}

} // namespace

TEST_CASE(
    "render: light shadow maps go to the spots and point lights that matter most to the camera's view") {
    NullScene s = nullScene();
    LightShadows shadows(*s.device);
    shadows.resize(2, 1, 256);
    std::vector<GpuPunctualLight> lights = {
        spotRecord({0.0f, 3.0f, -12.0f}, 40.0f, 6.0f),  // 0: in view, 12 m away: 40 / 153 = 0.26
        spotRecord({0.0f, 3.0f, 25.0f}, 1000.0f, 6.0f), // 1: brightest, but its reach is behind the camera
        spotRecord({2.0f, 3.0f, -4.0f}, 10.0f, 6.0f),   // 2: in view, 4.9 m: 10 / 21 = 0.48
        spotRecord({-2.0f, 3.0f, -8.0f}, 10.0f, 6.0f),  // 3: in view, 8.8 m: 10 / 69 = 0.14
    };
    // 4 and 5: point lights over the near floor's middle, the dimmer one nearer the camera.
    for (const auto& [z, intensity] : {std::pair{-8.0f, 500.0f}, std::pair{-3.0f, 20.0f}}) {
        GpuPunctualLight point = spotRecord({0.0f, 1.0f, z}, intensity, 6.0f);
        point.directionType.w = 1.0f;
        lights.push_back(point);
    }

    rhi::CommandList& cmd = s.device->beginFrame();
    const uint64_t triangles = shadows.render(cmd, *s.gpu, lights, s.camera, s.scene.bounds);
    s.device->endFrame();
    // The two most important spots (a view each), then the point light (six views): 500 / 66 = 7.6
    // against 20 / 10 = 2.
    CHECK(shadows.activeCount() == 3);
    CHECK(shadows.activeViews() == 8);
    CHECK(shadows.drawnViews() == 8); // every light sits in the view: all its views overlap it
    const LightShadowUniforms& u = shadows.uniforms();
    CHECK(u.count.x == 3);
    CHECK(u.light[0] == glm::ivec4(2, 0, 1, 0));
    CHECK(u.light[1] == glm::ivec4(0, 1, 1, 0));
    CHECK(u.light[2] == glm::ivec4(4, 2, 6, 0));
    // Each spot's view draws the near floor's 12 triangles, as do five of the point light's faces
    // (all but +y: the floor lies a metre below it and 6 m around); the floor behind the camera is
    // outside every view.
    CHECK(triangles == 2 * 12 + 5 * 12);
    CHECK(shadows.work().primitives == triangles);
    CHECK(shadows.work().texelsWritten == 8u * 256u * 256u);
    // Every view has its own tile of the 4 x 2 atlas.
    for (uint32_t v = 0; v < 8; ++v)
        CHECK(u.tile[v] == glm::vec4(float(v % 4) / 4.0f, float(v / 4) / 2.0f, 0.25f, 0.5f));

    // One spot and no point light: the most important spot alone.
    shadows.resize(1, 0, 256);
    shadows.render(s.device->beginFrame(), *s.gpu, lights, s.camera, s.scene.bounds);
    s.device->endFrame();
    CHECK(shadows.activeCount() == 1);
    CHECK(shadows.uniforms().light[0] == glm::ivec4(2, 0, 1, 0));
    // None: no atlas, nothing drawn, the lighting pass's binding gets the fallback.
    shadows.resize(0, 0, 256);
    rhi::CommandList& none = s.device->beginFrame();
    CHECK(shadows.render(none, *s.gpu, lights, s.camera, s.scene.bounds) == 0);
    s.device->endFrame();
    CHECK(shadows.activeCount() == 0);
    CHECK(shadows.atlas(rhi::TextureHandle{}) == rhi::TextureHandle{});
}

// Two spots of near-equal importance at the one place: the one with the map keeps it until the
// other matters kKeepFactor (1.5) times more, so small changes (a camera moving between them)
// do not make their shadows pop on and off from frame to frame; a clear change still moves it.
TEST_CASE("render: a light keeps its shadow map until another matters clearly more") {
    NullScene s = nullScene();
    LightShadows shadows(*s.device);
    shadows.resize(1, 0, 256);
    // Equally far from the camera, both in view: importance follows the intensities.
    std::vector<GpuPunctualLight> lights = {spotRecord({-2.0f, 3.0f, -6.0f}, 12.0f, 6.0f),
                                            spotRecord({2.0f, 3.0f, -6.0f}, 10.0f, 6.0f)};
    const auto chosen = [&](float first, float second) {
        lights[0].colorIntensity.w = first;
        lights[1].colorIntensity.w = second;
        shadows.render(s.device->beginFrame(), *s.gpu, lights, s.camera, s.scene.bounds);
        s.device->endFrame();
        REQUIRE(shadows.activeCount() == 1);
        return shadows.uniforms().light[0].x;
    };
    CHECK(chosen(12.0f, 10.0f) == 0); // the brighter
    CHECK(chosen(10.0f, 12.0f) == 0); // 1.2x: kept
    CHECK(chosen(10.0f, 14.5f) == 0); // 1.45x: kept
    CHECK(chosen(10.0f, 16.0f) == 1); // 1.6x: moves
    CHECK(chosen(12.0f, 10.0f) == 1); // and stays, the other way round
    CHECK(chosen(16.0f, 10.0f) == 0);
    // A new atlas (a settings or scene change) forgets: the brighter again.
    shadows.resize(1, 0, 256);
    CHECK(chosen(10.0f, 12.0f) == 1);
}

// A view that does not overlap the camera's lights no pixel the frame shows, so it is not drawn:
// of a point light 3 m behind the camera whose range reaches into the view only the face toward
// the view (-z) is drawn: a side face holds the points at least as far to its side as they are
// from the light along z, all outside the camera's 40 degrees to either side.
TEST_CASE("render: a light's shadow views that miss the camera's view are not drawn") {
    NullScene s = nullScene();
    LightShadows shadows(*s.device);
    shadows.resize(0, 1, 256);
    GpuPunctualLight point = spotRecord({0.0f, 1.0f, 3.0f}, 50.0f, 6.0f);
    point.directionType.w = 1.0f;
    const std::vector<GpuPunctualLight> lights = {point};
    shadows.render(s.device->beginFrame(), *s.gpu, lights, s.camera, s.scene.bounds);
    s.device->endFrame();
    REQUIRE(shadows.activeCount() == 1);
    CHECK(shadows.activeViews() == 6);
    CHECK(shadows.drawnViews() == 1);
    // In front of the camera, all six.
    GpuPunctualLight ahead = point;
    ahead.positionRange.z = -6.0f;
    const std::vector<GpuPunctualLight> inView = {ahead};
    shadows.render(s.device->beginFrame(), *s.gpu, inView, s.camera, s.scene.bounds);
    s.device->endFrame();
    CHECK(shadows.drawnViews() == 6);
}
