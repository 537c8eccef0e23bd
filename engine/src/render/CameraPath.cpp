// Scripted camera paths.
#include "engine/render/CameraPath.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>
#include <stdexcept>

namespace lpv::engine {

std::vector<std::string> cameraPathNames() {
    return {"orbit", "flythrough"};
}

bool isCameraPath(std::string_view name) {
    return name == "orbit" || name == "flythrough";
}

Camera cameraOnPath(std::string_view name, const Bounds& bounds, const Camera& start, float t) {
    Camera cam = start;
    const glm::vec3 c = bounds.center(), size = bounds.size();
    if (name == "orbit") {
        // The scene's camera carried once around the vertical axis through the scene's centre, its
        // distance, height and view turning with it, so that a run's first and last frames (the
        // screenshot) show the view the scene chose: a camera looking at the centre keeps looking
        // at it, one on the axis turns on the spot.
        const float a = glm::two_pi<float>() * t, ca = std::cos(a), sa = std::sin(a);
        const auto turn = [&](glm::vec3 v) {
            return glm::vec3(ca * v.x + sa * v.z, v.y, ca * v.z - sa * v.x);
        };
        cam.position = c + turn(start.position - c);
        cam.forward = glm::normalize(turn(start.forward));
    } else if (name == "flythrough") {
        // Along the longer horizontal axis at eye height, swaying side to side.
        const bool alongX = size.x >= size.z;
        const float s = (t - 0.5f) * 0.8f;
        const float sway = 0.15f * std::sin(t * glm::two_pi<float>());
        const glm::vec3 axis = alongX ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
        const glm::vec3 side = alongX ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
        cam.position = glm::vec3(c.x, bounds.min.y + 1.7f, c.z) + axis * s * glm::dot(size, axis) +
                       side * sway * glm::dot(size, side);
        cam.forward =
            glm::normalize(axis + side * 0.3f * std::cos(t * glm::two_pi<float>()) + glm::vec3(0, 0.05f, 0));
    } else {
        throw std::invalid_argument("unknown camera path '" + std::string(name) + "' (orbit, flythrough)");
    }
    cam.up = {0, 1, 0};
    return cam;
}

} // namespace lpv::engine
