// Camera matrices with depth 0..1 and row 0 at the top.
#include "engine/render/CameraMatrices.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/gtc/matrix_transform.hpp>

namespace lpv::engine {

CameraMatrices cameraMatrices(const Camera& camera, float aspect) {
    CameraMatrices m;
    m.position = camera.position;
    m.forward = glm::normalize(camera.forward);
    m.view = glm::lookAt(camera.position, camera.position + m.forward, camera.up);
    m.projection = glm::perspectiveRH_ZO(camera.verticalFov, aspect, camera.nearPlane, camera.farPlane);
    m.projection[1][1] *= -1.0f; // NDC y = -1 is image row 0, the top
    m.viewProjection = m.projection * m.view;
    m.invViewProjection = glm::inverse(m.viewProjection);
    return m;
}

} // namespace lpv::engine
