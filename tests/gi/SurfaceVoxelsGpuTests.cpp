// gi.gather's visibility (gi/SurfaceVoxels.h): the built-in Cornell box drawn onto a cascade's cell
// faces. Marched as vpl_visibility.glsl marches them, segments through open space stay open and
// every segment that leaves a solid (the boxes, whose tops and backs neither the camera nor the sun
// sees, and the floor slab) is blocked, at every angle: the faces along all three axes close the
// staircase a rotated box makes of the cells. Between two surfaces, the march the gather runs
// (its shader) sees past each surface's own face, where a surface lies on cells' centres too. On
// each backend.
#include "../support/TestDevice.h"
#include "TestShaders.h"
#include "engine/render/GpuScene.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/SurfaceVoxels.h"

#include <doctest/doctest.h>
#include <glm/common.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <random>
#include <utility>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

// The room (5.5 m a side, slabs 0.1 m thick) inside 32 cells of 0.2 m, off the half cells.
const gi::VolumeGrid kGrid{{-3.23f, -0.57f, -3.19f}, 0.2f, 32};

struct Faces {
    std::vector<uint32_t> texels; // (3 x + axis, y, z)
    uint32_t stamp = 0;
    bool blocked(glm::ivec3 c, int axis) const {
        const size_t n = kGrid.size;
        return texels[(size_t(c.z) * n + size_t(c.y)) * 3 * n + 3 * size_t(c.x) + size_t(axis)] == stamp;
    }
};

// vpl_visibility.glsl's march: whether b sees a.
bool visible(const Faces& faces, glm::vec3 a, glm::vec3 b) {
    const int n = int(kGrid.size);
    const glm::vec3 ta = (a - kGrid.origin) / kGrid.cellSize, tb = (b - kGrid.origin) / kGrid.cellSize;
    glm::ivec3 c = glm::ivec3(glm::floor(ta));
    const glm::vec3 d = tb - ta;
    const glm::ivec3 st = glm::ivec3(glm::sign(d));
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
        if (faces.blocked(upper, axis)) return false;
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
TEST_CASE("gi: a march between two surfaces sees past each one's own face") {
    const engine::Scene scene = engine::buildBuiltinScene("cornell");
    const gi::VolumeGrid grid{{-3.25f, -0.4f, -3.25f}, 0.2f, 32};
    struct Segment {
        glm::vec4 a, na, b, nb;
    };
    // Points on the ceiling (around its opening), on the red and back walls above the tall box
    // (3.3 m), and on the floor by the red wall, clear of the boxes; pairs that see each other.
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> across(-2.5f, 2.5f), high(3.6f, 5.3f), byWall(-2.5f, -2.0f),
        front(1.0f, 2.5f);
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
    }
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            const engine::GpuScene gpu(*device, scene);
            gi::SurfaceVoxels voxels(*device, grid.size);
            const uint64_t bytes = segments.size() * sizeof(Segment);
            const BufferHandle buffer = device->createBuffer(
                {bytes, kBufferStorage | kBufferTransfer, MemoryAccess::GpuOnly, "march segments", "test"},
                segments.data());
            const ComputePipelineHandle pipeline =
                device->createPipeline(ComputePipelineDesc{&shaders::surface_march_comp, "surface march"});
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
            std::vector<Segment> out(segments.size());
            device->readBuffer(buffer, 0, out.data(), bytes);
            int open = 0;
            for (const Segment& m : out)
                open += m.a.w > 0.5f;
            MESSAGE(backend.name << ": " << open << " of " << out.size()
                                 << " segments between surfaces open");
            CHECK(open == int(out.size()));
            device->destroy(pipeline);
            device->destroy(buffer);
            device.expectSilent();
        }
    }
}
