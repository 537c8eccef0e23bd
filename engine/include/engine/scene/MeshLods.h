// Coarser versions of a mesh for views that cannot resolve its detail: a reflective shadow map's
// texel is 0.1-1 m across, where a column's mouldings or a floor's subdivision are centimetres.
// Made with meshoptimizer's simplifier, which keeps attribute seams; each level's error is then
// measured on the geometry, so a view picks the coarsest level whose error is under its texel.
#pragma once

#include "engine/scene/Scene.h"

#include <cstdint>
#include <vector>

namespace lpv::engine {

// One level: an index range into the same vertices as the mesh, and how far it strays from the
// full mesh (m, in the mesh's own space): the largest distance from a vertex of the full mesh to
// the level's surface (at least the finer levels' errors).
struct MeshLod {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    float error = 0.0f;
};

// Each level keeps at most this share of the previous one's triangles, or it is not worth a level.
inline constexpr float kLodMinReduction = 0.75f;
// The full mesh and up to three coarser levels.
inline constexpr uint32_t kMaxMeshLods = 4;

// The levels of `mesh` coarser than itself, finest first, at relative errors that grow 4x per
// level (0.5%, 2%, 8% of the mesh's extent); their indices are appended to `indices`. Empty when
// the mesh does not simplify (a box, a single quad).
std::vector<MeshLod> simplifyMesh(const Scene& scene, const Mesh& mesh, std::vector<uint32_t>& indices);

} // namespace lpv::engine
