// The built-in atrium: its triangle budget per detail, well-formed geometry and textures, the
// materials the issue asks for, a sun that reaches the court floor, and determinism.
#include "engine/scene/BuiltinScenes.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstring>
#include <vector>

using namespace lpv::engine;

namespace {

void checkWellFormed(const Scene& s) {
    REQUIRE(!s.vertices.empty());
    size_t badVertices = 0;
    for (const Vertex& v : s.vertices) {
        const float n = glm::length(v.normal), t = glm::length(glm::vec3(v.tangent));
        const bool finite = std::isfinite(v.position.x) && std::isfinite(v.position.y) &&
                            std::isfinite(v.position.z) && std::isfinite(v.uv.x) && std::isfinite(v.uv.y);
        if (!finite || !(std::fabs(n - 1.0f) < 1e-3f) || !(std::fabs(t - 1.0f) < 1e-3f) ||
            std::fabs(std::fabs(v.tangent.w) - 1.0f) > 1e-6f)
            ++badVertices;
    }
    CHECK(badVertices == 0);
    size_t badIndices = 0;
    for (uint32_t i : s.indices)
        badIndices += i >= s.vertices.size();
    CHECK(badIndices == 0);
    for (const Mesh& m : s.meshes) {
        CHECK(m.indexCount % 3 == 0);
        CHECK(m.indexCount > 0);
        CHECK(uint64_t(m.firstIndex) + m.indexCount <= s.indices.size());
        CHECK(m.material < s.materials.size());
        CHECK_FALSE(m.bounds.empty());
    }
    for (const Instance& inst : s.instances) {
        REQUIRE(inst.mesh < s.meshes.size());
        const Bounds expected = s.meshes[inst.mesh].bounds.transformed(inst.transform);
        CHECK(glm::length(inst.worldBounds.min - expected.min) < 1e-4f);
        CHECK(glm::length(inst.worldBounds.max - expected.max) < 1e-4f);
    }
    for (const TextureImage& t : s.textures) {
        CHECK(t.width >= 128);
        CHECK(t.width <= 512);
        CHECK(t.height >= 128);
        CHECK(t.height <= 512);
        CHECK(t.rgba.size() == size_t(t.width) * t.height * 4);
    }
    for (const Material& m : s.materials) {
        CHECK(m.baseColorTexture < int32_t(s.textures.size()));
        CHECK(m.normalTexture < int32_t(s.textures.size()));
        if (m.normalTexture >= 0) CHECK_FALSE(s.textures[size_t(m.normalTexture)].srgb);
        CHECK(m.roughness >= 0.0f);
        CHECK(m.roughness <= 1.0f);
        CHECK(m.metallic >= 0.0f);
        CHECK(m.metallic <= 1.0f);
    }
}

bool rayHitsTriangle(glm::vec3 o, glm::vec3 d, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (std::fabs(det) < 1e-12f) return false;
    const glm::vec3 t = o - a;
    const float u = glm::dot(t, p) / det;
    if (u < 0.0f || u > 1.0f) return false;
    const glm::vec3 q = glm::cross(t, e1);
    const float v = glm::dot(d, q) / det;
    return v >= 0.0f && u + v <= 1.0f && glm::dot(e2, q) / det > 1e-3f;
}

// Fraction of points (x from -13 to 13, at height y and depth z) that see the sun.
float sunlitFraction(const Scene& s, float y, float z) {
    std::vector<glm::vec3> world;
    for (const Instance& inst : s.instances) {
        const Mesh& m = s.meshes[inst.mesh];
        for (uint32_t k = m.firstIndex; k < m.firstIndex + m.indexCount; ++k)
            world.push_back(glm::vec3(inst.transform * glm::vec4(s.vertices[s.indices[k]].position, 1.0f)));
    }
    const glm::vec3 toSun = -glm::normalize(s.lights.at(0).direction);
    int lit = 0, total = 0;
    for (float x = -13.0f; x <= 13.0f; x += 2.0f, ++total) {
        bool blocked = false;
        for (size_t k = 0; k < world.size() && !blocked; k += 3)
            blocked = rayHitsTriangle({x, y + 0.01f, z}, toSun, world[k], world[k + 1], world[k + 2]);
        lit += !blocked;
    }
    return float(lit) / float(total);
}

} // namespace

TEST_CASE("atrium: about 250k triangles at detail 1, scaling down with detail") {
    const Scene full = buildAtrium(1.0f);
    CHECK(full.name == "atrium");
    CHECK(full.triangleCount() >= 220000);
    CHECK(full.triangleCount() <= 290000);
    const Scene half = buildAtrium(0.5f), quarter = buildAtrium(0.25f), tenth = buildAtrium(0.1f);
    CHECK(half.triangleCount() < full.triangleCount());
    CHECK(quarter.triangleCount() < half.triangleCount());
    CHECK(quarter.triangleCount() < 80000);
    CHECK(tenth.triangleCount() < quarter.triangleCount());
    // Detail changes tessellation only, never the objects.
    CHECK(tenth.instances.size() == full.instances.size());
    CHECK(tenth.meshes.size() == full.meshes.size());
    CHECK(full.instances.size() >= 20);
    CHECK(full.instances.size() <= 400);
}

TEST_CASE("atrium: geometry, textures and materials are well formed at every detail") {
    for (float detail : {1.0f, 0.25f, 0.1f, 0.0f}) {
        CAPTURE(detail);
        const Scene s = buildAtrium(detail);
        checkWellFormed(s);
        CHECK(s.triangleCount() > 0);
    }
}

TEST_CASE("atrium: court, materials, sun and camera") {
    const Scene s = buildAtrium(1.0f);
    // About 30 m x 12 m inside, floor at y = 0, two stories under a roof at about 10 m.
    CHECK(s.bounds.size().x == doctest::Approx(30.8f).epsilon(0.05));
    CHECK(s.bounds.size().z == doctest::Approx(12.8f).epsilon(0.05));
    CHECK(s.bounds.min.y < 0.0f);
    CHECK(s.bounds.max.y > 9.0f);

    int normalMaps = 0, fabrics = 0, polished = 0;
    for (const Material& m : s.materials) {
        normalMaps += m.normalTexture >= 0;
        fabrics += std::strncmp(m.name.c_str(), "fabric", 6) == 0 && m.baseColorTexture >= 0;
        polished += m.roughness < 0.5f && m.metallic == 0.0f;
    }
    CHECK(normalMaps >= 1);
    CHECK(fabrics == 4);
    CHECK(polished >= 1);

    REQUIRE(s.lights.size() == 1);
    CHECK(s.lights[0].type == LightType::Directional);
    CHECK(s.lights[0].direction.y < -0.5f);
    CHECK(s.lights[0].intensity == doctest::Approx(20.0f));
    REQUIRE(s.camera.has_value());
    CHECK(s.camera->position.y == doctest::Approx(1.7f));
    CHECK(std::fabs(s.camera->forward.x) > 0.9f); // looking along the court
    CHECK(s.camera->verticalFov == doctest::Approx(glm::radians(60.0f)));
    CHECK(s.camera->nearPlane == doctest::Approx(0.1f));
    CHECK(s.camera->farPlane == doctest::Approx(100.0f));
}

TEST_CASE("atrium: the sun reaches the court floor through the roof opening") {
    const Scene s = buildAtrium(0.1f);            // same layout, fewer triangles to trace
    CHECK(sunlitFraction(s, 0.0f, -2.5f) > 0.5f); // the strip along the -z arcade
    CHECK(sunlitFraction(s, 0.0f, -4.5f) > 0.1f); // into the -z arcade through its arches
    CHECK(sunlitFraction(s, 0.0f, 2.5f) == 0.0f); // in the +z roof's shadow
    CHECK(sunlitFraction(s, 5.3f, 5.0f) == 0.0f); // the +z upper gallery, under the roof
}

TEST_CASE("atrium: deterministic") {
    const Scene a = buildAtrium(0.5f), b = buildAtrium(0.5f);
    REQUIRE(a.vertices.size() == b.vertices.size());
    CHECK(std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vertex)) == 0);
    CHECK(a.indices == b.indices);
    REQUIRE(a.textures.size() == b.textures.size());
    for (size_t i = 0; i < a.textures.size(); ++i)
        CHECK(a.textures[i].rgba == b.textures[i].rgba);
}
