// The open space around a point: how far a scene's surfaces leave room along each axis, read from
// a coarse occupancy grid of its triangles made once per scene. The GI sizes its finest cascade to
// the room the camera stands in with it (gi.cell_size = auto).
#pragma once

#include "engine/scene/Scene.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace lpv::engine {

class OpenSpace {
public:
    OpenSpace() = default;
    // Voxels of the scene's largest side / `resolution`; every triangle marks the voxels it crosses.
    explicit OpenSpace(const Scene& scene, uint32_t resolution = 64);

    // The room `p` stands in, as a box that holds its surfaces: along each axis the free span
    // through `p`, out to the far side of the first occupied voxel on either side (in which the
    // surface that ends the span lies; a voxel is the scene's largest side / resolution: half a
    // metre on a 30 m ground), or to the scene's bounds where the way is open. The voxel `p` lies
    // in does not count, so a camera against a wall still sees its room. The scene's bounds where
    // `p` lies outside them; empty for an empty scene.
    Bounds roomAround(glm::vec3 p) const;
    bool empty() const { return occupied_.empty(); }

private:
    bool occupiedAt(glm::ivec3 v) const;
    void mark(glm::vec3 p);

    Bounds bounds_;
    glm::ivec3 size_{0};
    float voxel_ = 1.0f;
    std::vector<uint8_t> occupied_;
};

} // namespace lpv::engine
