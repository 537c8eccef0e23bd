// Levels of detail made by simplifying meshes (engine/scene/MeshLods.h).
#include "engine/render/GpuScene.h"
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"
#include "engine/scene/MeshLods.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

using namespace lpv::engine;

namespace {

float distanceToSegment(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
    const glm::vec3 ab = b - a;
    const float t = glm::clamp(glm::dot(p - a, ab) / std::max(glm::dot(ab, ab), 1e-20f), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}

// Distance from p to triangle abc, found another way than the engine's (which walks the Voronoi
// regions): the plane when p projects inside the triangle, else the nearest edge.
float distanceToTriangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float area2 = glm::length(n);
    if (area2 > 1e-12f) {
        const glm::vec3 u = n / area2;
        const glm::vec3 q = p - glm::dot(p - a, u) * u;
        const bool inside = glm::dot(glm::cross(b - a, q - a), u) >= 0 &&
                            glm::dot(glm::cross(c - b, q - b), u) >= 0 &&
                            glm::dot(glm::cross(a - c, q - c), u) >= 0;
        if (inside) return std::fabs(glm::dot(p - a, u));
    }
    return std::min({distanceToSegment(p, a, b), distanceToSegment(p, b, c), distanceToSegment(p, c, a)});
}

// The largest distance from a vertex of the full mesh to the surface of `lod`: how far the level
// strays where the full mesh has detail it dropped.
float strayDistance(const Scene& s, const Mesh& mesh, const std::vector<uint32_t>& indices,
                    const MeshLod& lod) {
    float worst = 0.0f;
    for (uint32_t i = mesh.firstIndex; i < mesh.firstIndex + mesh.indexCount; ++i) {
        const glm::vec3 p = s.vertices[s.indices[i]].position;
        float nearest = 1e30f;
        for (uint32_t k = lod.firstIndex; k < lod.firstIndex + lod.indexCount; k += 3)
            nearest = std::min(nearest, distanceToTriangle(p, s.vertices[indices[k]].position,
                                                           s.vertices[indices[k + 1]].position,
                                                           s.vertices[indices[k + 2]].position));
        worst = std::max(worst, nearest);
    }
    return worst;
}

} // namespace

TEST_CASE("mesh lods: a finely tessellated floor becomes two triangles; a box stays as it is") {
    Scene s;
    MeshBuilder b(s);
    b.begin("floor", 0);
    b.quad({0, 0, 0}, {0, 0, 4}, {4, 0, 0}, 32, 32);
    b.finish();
    b.begin("box", 0);
    b.box({0, 0, 0}, {1, 1, 1});
    b.finish();
    std::vector<uint32_t> indices = s.indices;
    const std::vector<MeshLod> floor = simplifyMesh(s, s.meshes[0], indices);
    REQUIRE(!floor.empty());
    CHECK(floor.front().indexCount == 6); // flat: nothing is lost, so the first level goes all the way
    CHECK(floor.front().error < 1e-4f);
    CHECK(simplifyMesh(s, s.meshes[1], indices).empty());
    // Levels index the scene's own vertices, after its indices.
    CHECK(floor.front().firstIndex == s.indices.size());
    CHECK(indices.size() == s.indices.size() + 6);
}

TEST_CASE("mesh lods: the atrium's levels stray no further than they report and cut triangles") {
    const Scene s = buildAtrium(0.25f);
    std::vector<uint32_t> indices = s.indices;
    uint64_t full = 0, coarsest = 0, simplified = 0;
    float worstExcess = 0.0f;
    for (const Mesh& mesh : s.meshes) {
        const std::vector<MeshLod> lods = simplifyMesh(s, mesh, indices);
        full += mesh.indexCount / 3;
        coarsest += (lods.empty() ? mesh.indexCount : lods.back().indexCount) / 3;
        simplified += !lods.empty();
        uint32_t previous = mesh.indexCount;
        float previousError = 0.0f;
        for (const MeshLod& lod : lods) {
            CHECK(lod.indexCount % 3 == 0);
            CHECK(float(lod.indexCount) <= kLodMinReduction * float(previous));
            CHECK(lod.error >= previousError);
            for (uint32_t k = lod.firstIndex; k < lod.firstIndex + lod.indexCount; ++k)
                REQUIRE(indices[k] < s.vertices.size());
            previous = lod.indexCount;
            previousError = lod.error;
        }
        // The reported error bounds what the level lost, measured here again on the geometry.
        if (!lods.empty()) {
            const float stray = strayDistance(s, mesh, indices, lods.back());
            worstExcess = std::max(worstExcess, stray - lods.back().error);
        }
    }
    MESSAGE("atrium (detail 0.25): " << full << " triangles in its meshes, " << coarsest
                                     << " at their coarsest; " << simplified << " of " << s.meshes.size()
                                     << " meshes simplify");
    CHECK(worstExcess <= 0.0f);
    CHECK(coarsest * 3 < full);
}

TEST_CASE("mesh lods: a draw picks the coarsest level within the error it is allowed") {
    GpuDraw d;
    d.lods[0] = {0, 300, 0.0f};
    d.lods[1] = {300, 120, 0.01f};
    d.lods[2] = {420, 30, 0.2f};
    d.lodCount = 3;
    CHECK(d.lodWithin(0.0f).indexCount == 300);
    CHECK(d.lodWithin(0.009f).indexCount == 300);
    CHECK(d.lodWithin(0.01f).indexCount == 120);
    CHECK(d.lodWithin(0.1f).indexCount == 120);
    CHECK(d.lodWithin(1.0f).indexCount == 30);
    d.lodCount = 1; // a mesh that did not simplify
    CHECK(d.lodWithin(1.0f).indexCount == 300);
}
