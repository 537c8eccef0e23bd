// The open space around a point (OpenSpace.h).
#include "engine/scene/OpenSpace.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::engine {

OpenSpace::OpenSpace(const Scene& scene, uint32_t resolution) {
    if (scene.bounds.empty()) return;
    bounds_ = scene.bounds;
    const glm::vec3 extent = bounds_.size();
    voxel_ = bounds_.largestSide() / float(resolution);
    if (!(voxel_ > 0.0f)) return;
    size_ = glm::max(glm::ivec3(glm::ceil(extent / voxel_)), glm::ivec3(1));
    occupied_.assign(size_t(size_.x) * size_.y * size_.z, 0);
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        for (uint32_t i = 0; i + 2 < mesh.indexCount; i += 3) {
            glm::vec3 v[3];
            for (uint32_t k = 0; k < 3; ++k) {
                const Vertex& vertex = scene.vertices[size_t(
                    mesh.vertexOffset + int32_t(scene.indices[mesh.firstIndex + i + k]))];
                v[k] = glm::vec3(instance.transform * glm::vec4(vertex.position, 1.0f));
            }
            // Points over the triangle at most half a voxel apart: every voxel it crosses is marked.
            const float longest =
                std::max({glm::length(v[1] - v[0]), glm::length(v[2] - v[1]), glm::length(v[0] - v[2])});
            const int steps = std::clamp(int(std::ceil(2.0f * longest / voxel_)), 1, 4096);
            for (int a = 0; a <= steps; ++a)
                for (int b = 0; a + b <= steps; ++b) {
                    const float s = float(a) / float(steps), t = float(b) / float(steps);
                    mark(v[0] + s * (v[1] - v[0]) + t * (v[2] - v[0]));
                }
        }
    }
}

void OpenSpace::mark(glm::vec3 p) {
    const glm::ivec3 c =
        glm::clamp(glm::ivec3(glm::floor((p - bounds_.min) / voxel_)), glm::ivec3(0), size_ - 1);
    occupied_[(size_t(c.z) * size_.y + c.y) * size_.x + c.x] = 1;
}

bool OpenSpace::occupiedAt(glm::ivec3 v) const {
    return occupied_[(size_t(v.z) * size_.y + v.y) * size_.x + v.x] != 0;
}

Bounds OpenSpace::roomAround(glm::vec3 p) const {
    if (occupied_.empty()) return Bounds{};
    for (int a = 0; a < 3; ++a)
        if (p[a] < bounds_.min[a] || p[a] > bounds_.max[a]) return bounds_;
    const glm::ivec3 start =
        glm::clamp(glm::ivec3(glm::floor((p - bounds_.min) / voxel_)), glm::ivec3(0), size_ - 1);
    Bounds span = bounds_;
    for (int a = 0; a < 3; ++a) {
        // The far side of the first occupied voxel beyond the start on each side, or the bounds.
        for (glm::ivec3 v = start; --v[a] >= 0;)
            if (occupiedAt(v)) {
                span.min[a] = bounds_.min[a] + float(v[a]) * voxel_;
                break;
            }
        for (glm::ivec3 v = start; ++v[a] < size_[a];)
            if (occupiedAt(v)) {
                span.max[a] = bounds_.min[a] + float(v[a] + 1) * voxel_;
                break;
            }
    }
    return span;
}

} // namespace lpv::engine
