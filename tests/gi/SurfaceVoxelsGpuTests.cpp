// gi.gather's visibility (gi/SurfaceVoxels.h): the built-in Cornell box drawn onto a cascade's cell
// faces. Marched as vpl_visibility.glsl marches them, segments through open space stay open and
// every segment that leaves a solid (the boxes, whose tops and backs neither the camera nor the sun
// sees, and the floor slab) is blocked, at every angle: the faces along all three axes close the
// staircase a rotated box makes of the cells. Between two surfaces, the march the gather runs
// (its shader) sees past each surface's own face, where a surface lies on cells' centres too, and
// from a point between a surface and the face it marks. On each backend. Each face also adds up
// the area its surfaces cover (areas()), sample by sample, and holds where its surface lies.
#include "../support/TestDevice.h"
#include "TestShaders.h"
#include "engine/render/GpuScene.h"
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"
#include "gi/SurfaceVoxels.h"

#include <doctest/doctest.h>
#include <glm/common.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

// The room (5.5 m a side, slabs 0.1 m thick) inside 32 cells of 0.2 m, off the half cells.
const gi::VolumeGrid kGrid{{-3.23f, -0.57f, -3.19f}, 0.2f, 32};

// Where the surface that marked a face word lies, in cells from the face (surface_faces.glsl).
float planeOffset(uint32_t word) {
    constexpr uint32_t bits = gi::SurfaceVoxels::kPlaneBits;
    return (float(word & ((1u << bits) - 1u)) + 0.5f) / float(1u << bits) - 0.5f;
}

struct Faces {
    std::vector<uint32_t> texels; // (3 x + axis, y, z)
    uint32_t stamp = 0;
    // Whether the lower face along `axis` of cell c blocks a segment spanning `span` cells along it.
    bool blocked(glm::ivec3 c, int axis, glm::vec2 span) const {
        const size_t n = kGrid.size;
        const uint32_t word =
            texels[(size_t(c.z) * n + size_t(c.y)) * 3 * n + 3 * size_t(c.x) + size_t(axis)];
        if (word >> gi::SurfaceVoxels::kPlaneBits != stamp) return false;
        const float plane = float(c[axis]) + planeOffset(word);
        return span.x < plane && plane < span.y;
    }
};

// vpl_visibility.glsl's march: whether b sees a.
bool visible(const Faces& faces, glm::vec3 a, glm::vec3 b) {
    const int n = int(kGrid.size);
    const glm::vec3 ta = (a - kGrid.origin) / kGrid.cellSize, tb = (b - kGrid.origin) / kGrid.cellSize;
    glm::ivec3 c = glm::ivec3(glm::floor(ta));
    const glm::vec3 d = tb - ta;
    const glm::ivec3 st = glm::ivec3(glm::sign(d));
    const glm::vec3 lo = glm::min(ta, tb), hi = glm::max(ta, tb);
    const glm::vec3 inv = 1.0f / glm::max(glm::abs(d), glm::vec3(1e-6f));
    glm::vec3 tMax;
    for (int k = 0; k < 3; ++k)
        tMax[k] = (d[k] > 0.0f ? float(c[k] + 1) - ta[k] : ta[k] - float(c[k])) * inv[k];
    for (int i = 0; i < 3 * n; ++i) {
        const int axis = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
        if (tMax[axis] > 1.0f) break;
        glm::ivec3 upper = c;
        if (st[axis] > 0) upper[axis] += 1;
        if (glm::any(glm::lessThan(upper, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(upper, glm::ivec3(n))))
            break;
        if (faces.blocked(upper, axis, {lo[axis], hi[axis]})) return false;
        c[axis] += st[axis];
        tMax[axis] += inv[axis];
    }
    return true;
}

// A point inside box `half` (m) about `centre`, turned by `degrees` about y.
glm::vec3 inBox(std::mt19937& rng, glm::vec3 centre, glm::vec3 half, float degrees) {
    std::uniform_real_distribution<float> u(-0.7f, 0.7f); // over a cell from its sides
    const glm::vec3 local(u(rng) * half.x, 0.5f + u(rng) * 0.4f, u(rng) * half.z);
    const glm::mat4 m = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), {0, 1, 0});
    return centre + glm::vec3(m * glm::vec4(local.x, local.y * 2.0f * half.y, local.z, 1.0f));
}

} // namespace

TEST_CASE("gi: the surfaces' faces block what leaves a solid and nothing in open space") {
    const engine::Scene scene = engine::buildBuiltinScene("cornell");
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const engine::GpuScene gpu(*device, scene);
            gi::SurfaceVoxels voxels(*device, kGrid.size);
            rhi::CommandList& cmd = device->beginFrame();
            const uint64_t triangles = voxels.record(cmd, gpu, kGrid, 1);
            device->endFrame();
            device->waitIdle();
            Faces faces;
            faces.stamp = voxels.stamp(1);
            faces.texels.resize(size_t(3) * kGrid.size * kGrid.size * kGrid.size);
            device->readTexture(voxels.faces(1), 0, faces.texels.data(),
                                faces.texels.size() * sizeof(uint32_t));
            device.expectSilent();
            CHECK(triangles > 0);
            CHECK(faces.stamp != 0);
            CHECK(voxels.stamp(0) == 0); // cascade 0 not drawn: nothing blocks there

            std::mt19937 rng(7);
            std::uniform_real_distribution<float> across(-2.3f, 2.3f), high(3.75f, 5.05f);
            // Open space: above the tall box (3.3 m) and below the ceiling (5.5 m), two cells and
            // more from every surface.
            int open = 0;
            for (int i = 0; i < 300; ++i)
                open += visible(faces, {across(rng), high(rng), across(rng)},
                                {across(rng), high(rng), across(rng)});
            // Out of the boxes (turned 17 degrees) toward the open space and the walls, and from
            // below the floor into the room: a ray leaves through a side, a top or a slab.
            int blocked = 0, tried = 0;
            std::uniform_real_distribution<float> room(-2.3f, 2.3f), height(0.3f, 5.0f);
            for (int i = 0; i < 300; ++i) {
                const glm::vec3 to{room(rng), height(rng), room(rng)};
                const glm::vec3 from =
                    i % 3 == 0   ? inBox(rng, {-0.9f, 0.0f, -0.9f}, {0.825f, 1.65f, 0.825f}, 17.0f)
                    : i % 3 == 1 ? inBox(rng, {0.95f, 0.0f, 0.75f}, {0.825f, 0.825f, 0.825f}, -17.0f)
                                 : glm::vec3(room(rng), -0.45f, room(rng));
                // Only targets outside the boxes (a cell clear of them).
                const auto inside = [&](glm::vec3 centre, float half, float top, float degrees) {
                    const glm::mat4 m = glm::rotate(glm::mat4(1.0f), glm::radians(-degrees), {0, 1, 0});
                    const glm::vec3 l = glm::vec3(m * glm::vec4(to - centre, 1.0f));
                    return std::fabs(l.x) < half + 0.3f && std::fabs(l.z) < half + 0.3f && l.y < top + 0.3f;
                };
                if (inside({-0.9f, 0.0f, -0.9f}, 0.825f, 3.3f, 17.0f) ||
                    inside({0.95f, 0.0f, 0.75f}, 0.825f, 1.65f, -17.0f))
                    continue;
                ++tried;
                blocked += !visible(faces, to, from);
            }
            MESSAGE(backend.name << ": " << triangles << " triangles; open space " << open << "/300 open; "
                                 << blocked << "/" << tried << " segments out of a solid blocked");
            CHECK(open == 300);
            CHECK(tried > 150);
            CHECK(blocked == tried);
        }
    }
}

// The ceiling (5.5 m) and the red and back walls (-2.75 m) on cells' centres, as the engine's
// volume placed them in the built-in box: each marks the face half a cell behind it or the one
// half a cell in front, as the last bit of its position falls. The gather marches between two
// surfaces from past their own faces (vpl_visibility.glsl's surfaceVisibility): started exactly
// half a cell out, on the face in front, a share of these segments was blocked by the surfaces
// they start from, and the built-in box's ceiling took 10% less of the sunlit floor's light.
// And in cells off them, the red wall and the floor 0.4 cell behind the faces they mark, 8 cm in
// front of them: from the floor within 5 cm of the wall and the wall within 5 cm of the floor,
// between each surface and the other's face, the room was out of sight (the foot of the built-in
// box's sunlit red wall lit as the cells fell, docs/gi-fidelity.md).
TEST_CASE("gi: a march between two surfaces sees past each one's own face and from its foot") {
    const engine::Scene scene = engine::buildBuiltinScene("cornell");
    const std::array<gi::VolumeGrid, 2> grids{gi::VolumeGrid{{-3.25f, -0.4f, -3.25f}, 0.2f, 32},
                                              gi::VolumeGrid{{-3.27f, -0.52f, -3.19f}, 0.2f, 32}};
    struct Segment {
        glm::vec4 a, na, b, nb;
    };
    // Points on the ceiling (around its opening), on the red and back walls above the tall box
    // (3.3 m), and on the floor by the red wall, clear of the boxes; pairs that see each other.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> across(-2.5f, 2.5f), high(3.6f, 5.3f), byWall(-2.5f, -2.0f),
        front(1.0f, 2.5f), foot(0.005f, 0.05f), outward(-2.0f, -1.2f);
    const auto ceiling = [&] {
        glm::vec3 p{across(rng), 5.5f, across(rng)};
        while (std::fabs(p.x) < 0.75f && std::fabs(p.z) < 0.75f)
            p = {across(rng), 5.5f, across(rng)};
        return std::pair{glm::vec4(p, 0.0f), glm::vec4(0.0f, -1.0f, 0.0f, 0.0f)};
    };
    const auto redWall = [&] {
        return std::pair{glm::vec4(-2.75f, high(rng), across(rng), 0.0f), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f)};
    };
    const auto backWall = [&] {
        return std::pair{glm::vec4(across(rng), high(rng), -2.75f, 0.0f), glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)};
    };
    const auto floorByWall = [&] {
        return std::pair{glm::vec4(byWall(rng), 0.0f, front(rng), 0.0f), glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)};
    };
    const auto ceilingByWall = [&] {
        return std::pair{glm::vec4(byWall(rng), 5.5f, front(rng), 0.0f), glm::vec4(0.0f, -1.0f, 0.0f, 0.0f)};
    };
    // The floor at the red wall's foot, the wall at the floor's edge, and the floor out from it.
    const auto floorAtFoot = [&] {
        return std::pair{glm::vec4(-2.75f + foot(rng), 0.0f, front(rng), 0.0f),
                         glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)};
    };
    const auto wallAtFoot = [&] {
        return std::pair{glm::vec4(-2.75f, foot(rng), front(rng), 0.0f), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f)};
    };
    const auto floorOut = [&] {
        return std::pair{glm::vec4(outward(rng), 0.0f, front(rng), 0.0f), glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)};
    };
    std::vector<Segment> segments;
    for (int i = 0; i < 100; ++i) {
        const auto [c, nc] = ceiling();
        const auto [r, nr] = redWall();
        const auto [k, nk] = backWall();
        const auto [f, nf] = floorByWall();
        const auto [u, nu] = ceilingByWall();
        segments.push_back({c, nc, r, nr});
        segments.push_back({k, nk, c, nc});
        segments.push_back({r, nr, k, nk});
        segments.push_back({f, nf, u, nu});
        const auto [g, ng] = floorAtFoot();
        const auto [w, nw] = wallAtFoot();
        const auto [o, no] = floorOut();
        segments.push_back({g, ng, u, nu});
        segments.push_back({g, ng, r, nr});
        segments.push_back({w, nw, u, nu});
        segments.push_back({w, nw, o, no});
    }
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            const engine::GpuScene gpu(*device, scene);
            const ComputePipelineHandle pipeline =
                device->createPipeline(ComputePipelineDesc{&shaders::surface_march_comp, "surface march"});
            for (const gi::VolumeGrid& grid : grids) {
                gi::SurfaceVoxels voxels(*device, grid.size);
                const uint64_t bytes = segments.size() * sizeof(Segment);
                const BufferHandle buffer =
                    device->createBuffer({bytes, kBufferStorage | kBufferTransfer, MemoryAccess::GpuOnly,
                                          "march segments", "test"},
                                         segments.data());
                CommandList& cmd = device->beginFrame();
                voxels.record(cmd, gpu, grid, 0);
                struct {
                    glm::vec4 origin;
                    glm::uvec4 grid;
                } u{glm::vec4(grid.origin, grid.cellSize), glm::uvec4(grid.size, voxels.stamp(0), 0u, 0u)};
                cmd.bindPipeline(pipeline);
                cmd.pushUniforms(0, &u, sizeof(u));
                cmd.bindStorageBuffer(1, buffer, 0, bytes);
                cmd.bindStorageImage(2, voxels.faces(0));
                cmd.dispatch(uint32_t(segments.size()));
                device->endFrame();
                device->waitIdle();
                std::vector<Segment> marched(segments.size());
                device->readBuffer(buffer, 0, marched.data(), bytes);
                int open = 0;
                for (const Segment& m : marched)
                    open += m.a.w > 0.5f;
                MESSAGE(backend.name << ", grid at " << grid.origin.x << ", " << grid.origin.y << ": " << open
                                     << " of " << marched.size() << " segments between surfaces open");
                CHECK(open == int(marched.size()));
                device->destroy(buffer);
            }
            device->destroy(pipeline);
            device.expectSilent();
        }
    }
}

// Two rectangles off the cells' sides, one facing up and one facing +x: each face holds the
// number of its column's 3 x 3 samples the rectangle covers (an area to a ninth of a face, its
// rim's faces partly covered), and no other face anything; the middle sample alone marks a face
// blocked, as a column's centre line did before the areas.
TEST_CASE("gi: each face adds up the samples of the surfaces that cross it") {
    constexpr uint32_t k = gi::SurfaceVoxels::kSamplesPerSide;
    static_assert(k == 3);
    const gi::VolumeGrid grid{{-4.0f, -4.0f, -4.0f}, 0.25f, 32};
    struct Rectangle {
        int axis;         // the one it faces along
        float at;         // its position along it (m)
        glm::vec2 lo, hi; // its extent along the two others, in axis order (m)
    };
    // The floor at y 0.1 (cells 16.4: face 16) over x -1.3..2.2, z -0.9..1.7; the wall at x 0.6
    // (18.4: face 18) over y 0.3..1.8, z -2.2..-1.1.
    const std::array<Rectangle, 2> rectangles{
        {{1, 0.1f, {-1.3f, -0.9f}, {2.2f, 1.7f}}, {0, 0.6f, {0.3f, -2.2f}, {1.8f, -1.1f}}}};
    engine::Scene scene;
    scene.name = "two rectangles";
    scene.materials = {{"white", {0.8f, 0.8f, 0.8f, 1.0f}}};
    engine::MeshBuilder builder(scene);
    builder.begin("floor", 0);
    builder.quad({-1.3f, 0.1f, 1.7f}, {3.5f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.6f}); // faces +y
    builder.finish();
    builder.begin("wall", 0);
    builder.quad({0.6f, 0.3f, -1.1f}, {0.0f, 0.0f, -1.1f}, {0.0f, 1.5f, 0.0f}); // faces +x
    builder.finish();
    scene.updateBounds();

    // Per face texel (3 x + axis, y, z): the samples covered, and whether the middle one is.
    const size_t n = grid.size;
    std::vector<uint32_t> expected(3 * n * n * n, 0u);
    std::vector<uint8_t> middle(expected.size(), 0u);
    std::vector<float> planes(expected.size(), 0.0f); // where the surface lies off the face, in cells
    const auto toCells = [&](float m, int axis) { return (m - grid.origin[axis]) / grid.cellSize; };
    for (const Rectangle& r : rectangles) {
        const int u = r.axis == 0 ? 1 : 0, v = r.axis == 2 ? 1 : 2;
        const int face = int(std::floor(toCells(r.at, r.axis) + 0.5f));
        for (size_t i = 0; i < n; ++i)
            for (size_t j = 0; j < n; ++j) {
                uint32_t covered = 0;
                bool centre = false;
                for (uint32_t a = 0; a < k; ++a)
                    for (uint32_t b = 0; b < k; ++b) {
                        const float su = float(i) + (float(a) + 0.5f) / float(k);
                        const float sv = float(j) + (float(b) + 0.5f) / float(k);
                        const bool in = su > toCells(r.lo.x, u) && su < toCells(r.hi.x, u) &&
                                        sv > toCells(r.lo.y, v) && sv < toCells(r.hi.y, v);
                        covered += in;
                        centre = centre || (in && a == k / 2 && b == k / 2);
                    }
                glm::ivec3 c(0);
                c[r.axis] = face;
                c[u] = int(i);
                c[v] = int(j);
                const size_t at = (size_t(c.z) * n + size_t(c.y)) * 3 * n + 3 * size_t(c.x) + size_t(r.axis);
                expected[at] += covered;
                middle[at] = middle[at] || centre;
                planes[at] = toCells(r.at, r.axis) - float(face);
            }
    }
    uint32_t partial = 0, whole = 0;
    for (uint32_t e : expected) {
        partial += e > 0 && e < k * k;
        whole += e == k * k;
    }
    REQUIRE(partial > 20);
    REQUIRE(whole > 100);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const engine::GpuScene gpu(*device, scene);
            // Twice: the second pass counts from nothing (no clear between). With the stamps
            // limited to 1 and 2, five passes: the third and the fifth start the stamps again,
            // and count from nothing too (the faces' clear at the wrap).
            for (const auto& [limit, passes] :
                 {std::pair{gi::SurfaceVoxels::kStampLimit, 2}, std::pair{3u, 5}}) {
                gi::SurfaceVoxels voxels(*device, grid.size, limit);
                for (int pass = 0; pass < passes; ++pass) {
                    rhi::CommandList& cmd = device->beginFrame();
                    voxels.record(cmd, gpu, grid, 0);
                    device->endFrame();
                }
                device->waitIdle();
                std::vector<uint32_t> areas(expected.size()), faces(expected.size());
                device->readTexture(voxels.areas(0), 0, areas.data(), areas.size() * sizeof(uint32_t));
                device->readTexture(voxels.faces(0), 0, faces.data(), faces.size() * sizeof(uint32_t));
                device.expectSilent();
                size_t wrongAreas = 0, wrongMarks = 0, wrongPlanes = 0;
                constexpr uint32_t bits = gi::SurfaceVoxels::kAreaCountBits;
                for (size_t t = 0; t < expected.size(); ++t) {
                    const uint32_t samples =
                        areas[t] >> bits == voxels.stamp(0) ? areas[t] & ((1u << bits) - 1u) : 0u;
                    wrongAreas += samples != expected[t];
                    const bool marked = faces[t] >> gi::SurfaceVoxels::kPlaneBits == voxels.stamp(0);
                    wrongMarks += marked != (middle[t] != 0);
                    wrongPlanes += marked && std::fabs(planeOffset(faces[t]) - planes[t]) > 1e-3f;
                }
                MESSAGE(backend.name << ", " << passes << " passes, stamp " << voxels.stamp(0) << ": "
                                     << whole << " faces whole, " << partial << " in part; " << wrongAreas
                                     << " areas, " << wrongMarks << " marks and " << wrongPlanes
                                     << " planes wrong");
                CHECK(wrongAreas == 0);
                CHECK(wrongMarks == 0);
                CHECK(wrongPlanes == 0);
            }
        }
    }
}
