// Scene bookkeeping: bounds and counts.
#include "engine/scene/Scene.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>

#include <array>

namespace lpv::engine {

void Bounds::add(glm::vec3 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
}

void Bounds::add(const Bounds& b) {
    if (b.empty()) return;
    add(b.min);
    add(b.max);
}

Bounds Bounds::transformed(const glm::mat4& m) const {
    Bounds out;
    if (empty()) return out;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner{(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
        out.add(glm::vec3(m * glm::vec4(corner, 1.0f)));
    }
    return out;
}

bool Bounds::outsideClipVolume(const glm::mat4& viewProjection) const {
    if (empty()) return true;
    std::array<glm::vec3, 8> corners;
    for (int i = 0; i < 8; ++i)
        corners[size_t(i)] = {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
    return lpv::engine::outsideClipVolume(corners, viewProjection);
}

bool outsideClipVolume(std::span<const glm::vec3> points, const glm::mat4& viewProjection) {
    uint32_t beyondAll = 0x3f; // a bit per plane that every point so far lies beyond
    for (size_t i = 0; i < points.size() && beyondAll; ++i) {
        const glm::vec4 c = viewProjection * glm::vec4(points[i], 1.0f);
        const uint32_t beyond = (c.x < -c.w ? 1u : 0u) | (c.x > c.w ? 2u : 0u) | (c.y < -c.w ? 4u : 0u) |
                                (c.y > c.w ? 8u : 0u) | (c.z < 0.0f ? 16u : 0u) | (c.z > c.w ? 32u : 0u);
        beyondAll &= beyond;
    }
    return !points.empty() && beyondAll != 0;
}

uint64_t Scene::triangleCount() const {
    uint64_t n = 0;
    for (const Instance& inst : instances)
        n += meshes[inst.mesh].indexCount / 3;
    return n;
}

void Scene::updateBounds() {
    bounds = Bounds{};
    for (Instance& inst : instances) {
        inst.worldBounds = meshes[inst.mesh].bounds.transformed(inst.transform);
        bounds.add(inst.worldBounds);
    }
}

Camera defaultCamera(const Scene& scene) {
    if (scene.camera) return *scene.camera;
    Camera cam;
    const glm::vec3 c = scene.bounds.center(), size = scene.bounds.size();
    cam.position = c + glm::vec3(0.0f, 0.1f * size.y, 0.9f * std::max(size.x, size.z) + 0.5f);
    cam.forward = glm::normalize(c - cam.position);
    cam.farPlane = std::max(100.0f, 4.0f * glm::length(size));
    return cam;
}

} // namespace lpv::engine
