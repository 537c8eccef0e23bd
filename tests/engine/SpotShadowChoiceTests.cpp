// Which spot lights get a shadow map (engine/render/SpotShadows.h), on the null device: the choice
// does not depend on a backend, and the null device counts what the pass draws.
#include "engine/render/SpotShadows.h"
#include "engine/scene/MeshBuilder.h"

#include "rhi/Device.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <cmath>
#include <memory>
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

TEST_CASE("render: spot shadow maps go to the spots that matter most to the camera's view") {
    NullScene s = nullScene();
    SpotShadows shadows(*s.device);
    shadows.resize(2, 256);
    const std::vector<GpuPunctualLight> lights = {
        spotRecord({0.0f, 3.0f, -12.0f}, 40.0f, 6.0f),  // 0: in view, 12 m away: 40 / 153 = 0.26
        spotRecord({0.0f, 3.0f, 25.0f}, 1000.0f, 6.0f), // 1: brightest, but its reach is behind the camera
        spotRecord({2.0f, 3.0f, -4.0f}, 10.0f, 6.0f),   // 2: in view, 4.9 m: 10 / 24 = 0.42
        spotRecord({-2.0f, 3.0f, -8.0f}, 10.0f, 6.0f),  // 3: in view, 8.8 m: 10 / 77 = 0.13
    };
    GpuPunctualLight point = spotRecord({0.0f, 1.0f, -3.0f}, 500.0f, 6.0f);
    point.directionType.w = 1.0f; // 4: a point light, bright and near: never a spot map
    std::vector<GpuPunctualLight> all = lights;
    all.push_back(point);

    rhi::CommandList& cmd = s.device->beginFrame();
    const uint64_t triangles = shadows.render(cmd, *s.gpu, all, s.camera, s.scene.bounds);
    s.device->endFrame();
    CHECK(shadows.activeCount() == 2);
    CHECK(shadows.uniforms().light == glm::ivec4(2, 0, -1, -1));
    // Each map draws the near floor's 12 triangles; the floor behind the camera is outside both.
    CHECK(triangles == 2 * 12);
    CHECK(shadows.work().primitives == triangles);
    CHECK(shadows.work().texelsWritten == 2u * 256u * 256u);

    // One map: the most important alone; none: nothing drawn, no light named.
    shadows.resize(1, 256);
    shadows.render(s.device->beginFrame(), *s.gpu, all, s.camera, s.scene.bounds);
    s.device->endFrame();
    CHECK(shadows.uniforms().light == glm::ivec4(2, -1, -1, -1));
    shadows.resize(0, 256);
    rhi::CommandList& none = s.device->beginFrame();
    CHECK(shadows.render(none, *s.gpu, all, s.camera, s.scene.bounds) == 0);
    s.device->endFrame();
    CHECK(shadows.activeCount() == 0);
    CHECK(shadows.uniforms().light == glm::ivec4(-1));
    // A map the lighting pass asks for that was not drawn is the fallback texture.
    CHECK(shadows.map(0, rhi::TextureHandle{}) == rhi::TextureHandle{});
}
