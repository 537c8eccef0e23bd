// The built-in "lights" scene: a hall at night lit by many small coloured point lights, the case
// the LPV's analytic lights are for (gi/PointLightInjection.h).
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <array>
#include <cmath>
#include <string>

namespace lpv::engine {

Scene buildLightHall(uint32_t pointLights) {
    Scene scene;
    scene.name = "lights";
    scene.materials = {{"floor", {0.75f, 0.75f, 0.75f, 1.0f}}, {"wall", {0.6f, 0.6f, 0.6f, 1.0f}}};
    constexpr uint32_t kFloor = 0, kWall = 1;
    // 7 m square, 2.5 m walls on three sides, open toward +z where the camera stands; the whole
    // hall fits the default 32 x 0.25 m volume.
    const float half = 3.5f, h = 2.5f, wall = 0.1f;
    MeshBuilder b(scene);
    b.begin("floor", kFloor);
    b.box({-half - wall, -wall, -half - wall}, {half + wall, 0.0f, half});
    b.finish();
    b.begin("walls", kWall);
    b.box({-half - wall, 0.0f, -half - wall}, {half + wall, h, -half});
    b.box({-half - wall, 0.0f, -half}, {-half, h, half});
    b.box({half, 0.0f, -half}, {half + wall, h, half});
    b.finish();

    // A dim moon, so the renderer does not fall back to its default sun.
    Light moon;
    moon.name = "moon";
    moon.type = LightType::Directional;
    moon.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    moon.color = {0.55f, 0.65f, 1.0f};
    moon.intensity = 0.3f;
    scene.lights.push_back(moon);

    // Point lights 0.3 m over the floor on a square grid; colour (i + 2 j) mod 6, so no light has
    // a neighbour (diagonals included) of its own colour.
    const std::array<glm::vec3, 6> palette{{{1.0f, 0.08f, 0.05f},
                                            {0.1f, 1.0f, 0.1f},
                                            {0.1f, 0.2f, 1.0f},
                                            {1.0f, 0.75f, 0.1f},
                                            {0.1f, 0.9f, 1.0f},
                                            {1.0f, 0.1f, 0.9f}}};
    const uint32_t side = uint32_t(std::ceil(std::sqrt(double(pointLights))));
    const float spacing = 6.4f / float(side);
    for (uint32_t k = 0; k < pointLights; ++k) {
        const uint32_t i = k % side, j = k / side;
        Light l;
        l.name = "light " + std::to_string(k);
        l.type = LightType::Point;
        l.position = {-3.2f + (float(i) + 0.5f) * spacing, 0.3f, -3.2f + (float(j) + 0.5f) * spacing};
        l.color = palette[(i + 2 * j) % palette.size()];
        l.intensity = 0.4f;
        l.range = 1.2f;
        scene.lights.push_back(l);
    }
    // Three spot lights high on the back wall, aimed down and forward.
    for (int s = -1; s <= 1; ++s) {
        Light l;
        l.name = "spot " + std::to_string(s + 1);
        l.type = LightType::Spot;
        l.position = {2.0f * float(s), 2.2f, -3.3f};
        l.direction = glm::normalize(glm::vec3(0.0f, -0.8f, 0.6f));
        l.color = {1.0f, 0.9f, 0.75f};
        l.intensity = 6.0f;
        l.range = 3.0f;
        l.innerConeAngle = 0.35f;
        l.outerConeAngle = 0.6f;
        scene.lights.push_back(l);
    }

    Camera cam;
    cam.position = {0.0f, 4.0f, 8.0f};
    cam.forward = glm::normalize(glm::vec3(0.0f, 0.3f, 0.0f) - cam.position);
    cam.verticalFov = glm::radians(50.0f);
    cam.nearPlane = 0.1f;
    cam.farPlane = 40.0f;
    scene.camera = cam;
    return scene;
}

} // namespace lpv::engine
