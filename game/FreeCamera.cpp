// Free-flying camera input.
#include "FreeCamera.h"

#include "platforms/Platform.h"

#include <GLFW/glfw3.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::game {

FreeCamera::FreeCamera(const engine::Camera& start) : camera_(start) {
    const glm::vec3 f = glm::normalize(start.forward);
    yaw_ = std::atan2(f.x, -f.z);
    pitch_ = std::asin(std::clamp(f.y, -1.0f, 1.0f));
}

bool FreeCamera::update(const platforms::Platform& platform, float seconds, float speed) {
    double dx = 0, dy = 0;
    platform.cursorDelta(dx, dy);
    yaw_ += float(dx) * 0.003f;
    pitch_ = std::clamp(pitch_ - float(dy) * 0.003f, -1.5f, 1.5f);
    const glm::vec3 forward(std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_),
                            -std::cos(yaw_) * std::cos(pitch_));
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    glm::vec3 move(0.0f);
    if (platform.keyDown(GLFW_KEY_W)) move += forward;
    if (platform.keyDown(GLFW_KEY_S)) move -= forward;
    if (platform.keyDown(GLFW_KEY_D)) move += right;
    if (platform.keyDown(GLFW_KEY_A)) move -= right;
    if (platform.keyDown(GLFW_KEY_E)) move += glm::vec3(0, 1, 0);
    if (platform.keyDown(GLFW_KEY_Q)) move -= glm::vec3(0, 1, 0);
    const float fast = platform.keyDown(GLFW_KEY_LEFT_SHIFT) ? 4.0f : 1.0f;
    const bool moved = dx != 0 || dy != 0 || glm::length(move) > 0;
    if (glm::length(move) > 0) camera_.position += glm::normalize(move) * speed * fast * seconds;
    camera_.forward = forward;
    return moved;
}

} // namespace lpv::game
