// View and projection of a scene camera in the engine's conventions: right-handed world, depth
// 0 (near) to 1 (far), image row 0 at the top (projection y flipped), identical on every backend.
#pragma once

#include "engine/scene/Scene.h"

#include <glm/mat4x4.hpp>

namespace lpv::engine {

struct CameraMatrices {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::mat4 viewProjection{1.0f};
    glm::mat4 invViewProjection{1.0f};
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
};

CameraMatrices cameraMatrices(const Camera& camera, float aspect);

} // namespace lpv::engine
