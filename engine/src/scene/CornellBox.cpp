// The built-in Cornell box (dimensions after the classic 555 mm box, in metres x 10).
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace lpv::engine {

Scene buildCornellBox() {
    Scene scene;
    scene.name = "cornell";
    // Reflectances close to the measured Cornell box paints.
    scene.materials = {
        {"white", {0.73f, 0.73f, 0.73f, 1.0f}},
        {"red", {0.65f, 0.05f, 0.05f, 1.0f}},
        {"green", {0.12f, 0.45f, 0.15f, 1.0f}},
        {"box", {0.73f, 0.73f, 0.73f, 1.0f}},
    };
    constexpr uint32_t kWhite = 0, kRed = 1, kGreen = 2, kBox = 3;
    const float h = 5.5f, half = 2.75f, wall = 0.1f, hole = 0.65f;
    MeshBuilder b(scene);

    // Walls are slabs, not planes, so shadow and occlusion tests see solid geometry.
    b.begin("floor", kWhite);
    b.box({-half - wall, -wall, -half - wall}, {half + wall, 0.0f, half});
    b.finish();
    b.begin("back wall", kWhite);
    b.box({-half - wall, 0.0f, -half - wall}, {half + wall, h, -half});
    b.finish();
    b.begin("red wall", kRed);
    b.box({-half - wall, 0.0f, -half}, {-half, h, half});
    b.finish();
    b.begin("green wall", kGreen);
    b.box({half, 0.0f, -half}, {half + wall, h, half});
    b.finish();
    // The ceiling is four slabs around a square opening in the middle.
    b.begin("ceiling", kWhite);
    b.box({-half - wall, h, -half - wall}, {-hole, h + wall, half});
    b.box({hole, h, -half - wall}, {half + wall, h + wall, half});
    b.box({-hole, h, -half - wall}, {hole, h + wall, -hole});
    b.box({-hole, h, hole}, {hole, h + wall, half});
    b.finish();

    b.begin("short box", kBox);
    b.box({-0.825f, 0.0f, -0.825f}, {0.825f, 1.65f, 0.825f});
    b.finish(
        glm::rotate(glm::translate(glm::mat4(1.0f), {0.95f, 0.0f, 0.75f}), glm::radians(-17.0f), {0, 1, 0}));
    b.begin("tall box", kBox);
    b.box({-0.825f, 0.0f, -0.825f}, {0.825f, 3.3f, 0.825f});
    b.finish(
        glm::rotate(glm::translate(glm::mat4(1.0f), {-0.9f, 0.0f, -0.9f}), glm::radians(17.0f), {0, 1, 0}));

    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    // Through the ceiling opening onto the floor by the red wall and the foot of that wall, so the
    // red wall reflects light (its colour bleeds onto the floor) and the boxes stay out of the beam.
    sun.direction = glm::normalize(glm::vec3(-0.45f, -1.0f, 0.25f));
    sun.color = {1.0f, 0.95f, 0.88f};
    sun.intensity = 20.0f;
    scene.lights.push_back(sun);

    Camera cam;
    cam.position = {0.0f, 2.75f, 10.6f};
    cam.forward = {0.0f, 0.0f, -1.0f};
    cam.verticalFov = glm::radians(38.0f);
    cam.nearPlane = 0.1f;
    cam.farPlane = 40.0f;
    scene.camera = cam;
    return scene;
}

} // namespace lpv::engine
