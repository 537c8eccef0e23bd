// The free camera: WASD to move (Q/E down/up, Shift faster), right mouse button to look. Without
// input (headless) it stays where it is.
#pragma once

#include "engine/scene/Scene.h"

namespace lpv::platforms {
class Platform;
}

namespace lpv::game {

class FreeCamera {
public:
    explicit FreeCamera(const engine::Camera& start);
    // Applies this frame's input; returns true when the camera moved.
    bool update(const platforms::Platform& platform, float seconds, float speed);
    const engine::Camera& camera() const { return camera_; }

private:
    engine::Camera camera_;
    float yaw_ = 0, pitch_ = 0;
};

} // namespace lpv::game
