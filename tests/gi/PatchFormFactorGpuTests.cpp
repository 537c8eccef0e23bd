// The gather's near-field patch (gi/shaders/patch_form_factor.glsl), on each backend: the form
// factor from a point to a rectangle, which the per-pixel gather takes for a VPL's cluster near a
// receiver, against the integral of cos x cos / (pi r^2) over the rectangle: facing it, at the
// foot of a wall over a lit floor (where a point VPL's kernel is near zero), across the
// receiver's horizon, behind it, and far away (where the gather switches to the point's kernel).
#include "../support/TestDevice.h"
#include "TestShaders.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cmath>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

struct Case {
    glm::vec4 receiver, normal, centre, facing, result;
};

// The rectangle's tangent as patchTangent() makes it: the world axis least along the normal.
glm::dvec3 tangentOf(glm::dvec3 m) {
    const glm::dvec3 a = std::abs(m.x) <= std::abs(m.y) && std::abs(m.x) <= std::abs(m.z)
                             ? glm::dvec3(1, 0, 0)
                         : std::abs(m.y) <= std::abs(m.z) ? glm::dvec3(0, 1, 0)
                                                          : glm::dvec3(0, 0, 1);
    return glm::normalize(a - m * glm::dot(a, m));
}

// The integral of cos x cos / (pi r^2) over the rectangle, where it is above the receiver's
// horizon and the receiver in front of it: midpoints of n x n pieces.
double integrated(const Case& c, int n = 2000) {
    const glm::dvec3 p(c.receiver), rn(c.normal), o(c.centre), m(glm::normalize(glm::dvec3(c.facing)));
    const glm::dvec3 t = tangentOf(m), b = glm::cross(m, t);
    const double ex = c.receiver.w, ey = c.normal.w, da = (2.0 * ex / n) * (2.0 * ey / n);
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const glm::dvec3 q =
                o + t * (ex * ((2.0 * i + 1.0) / n - 1.0)) + b * (ey * ((2.0 * j + 1.0) / n - 1.0));
            const glm::dvec3 v = q - p;
            const double r2 = glm::dot(v, v), r = std::sqrt(r2);
            const double at = glm::dot(rn, v) / r, from = -glm::dot(m, v) / r;
            if (at > 0.0 && from > 0.0) sum += at * from / (3.14159265358979 * r2) * da;
        }
    return sum;
}

Case make(glm::vec3 receiver, glm::vec3 normal, glm::vec3 centre, glm::vec3 facing, glm::vec2 extents) {
    return {glm::vec4(receiver, extents.x), glm::vec4(normal, extents.y), glm::vec4(centre, 0.0f),
            glm::vec4(facing, 0.0f), glm::vec4(0.0f)};
}

} // namespace

TEST_CASE("gi: a VPL's patch lights a point near it by its form factor") {
    std::vector<Case> cases = {
        // 0: a 1 m square facing the receiver 1 m away on its axis.
        make({0, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, -1, 0}, {0.5f, 0.5f}),
        // 1: the foot of a wall, 2 cm over a lit 1 m floor square that runs from the wall.
        make({0, 0.02f, 0}, {1, 0, 0}, {0.5f, 0, 0}, {0, 1, 0}, {0.5f, 0.5f}),
        // 2: a wall square in front of the receiver with a part under its horizon.
        make({0, 0, 0}, {0, 1, 0}, {0, 0.1f, 1}, {0, 0, -1}, {0.5f, 0.5f}),
        // 3: a square tilted 40 degrees, off the axis, with a part under the horizon.
        make({0.2f, 0, -0.1f}, {0, 1, 0}, {0.3f, 0.05f, 0.6f}, glm::normalize(glm::vec3(0, -0.64f, -0.77f)),
             {0.3f, 0.2f}),
        // 4: the receiver behind the square's plane.
        make({0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0.5f, 0.5f}),
        // 5: a 0.5 m square 2.5 m away (10 half extents: where the gather takes a point instead).
        make({0, 0, 0}, {0, 1, 0}, {0, 2.5f, 0}, {0, -1, 0}, {0.25f, 0.25f}),
    };
    std::array<double, 6> expected{};
    for (size_t i = 0; i < cases.size(); ++i)
        expected[i] = integrated(cases[i]);
    // The closed form for case 0: four times the corner of a 0.5 m square at 1 m (Howell's
    // catalogue, an element parallel to a rectangle on the normal through its corner).
    const double x = 0.5 / std::sqrt(1.25);
    const double corner = (2.0 * x * std::atan(x)) / (2.0 * 3.14159265358979);
    CHECK(expected[0] == doctest::Approx(4.0 * corner).epsilon(1e-4));
    // The wall's foot sees the floor fill most of the lower half of its hemisphere; a point at the
    // square's centre would give 0.25 m^2 x cos 0.04 x cos 1 / (pi 0.25) < 0.02.
    CHECK(expected[1] > 0.35);
    CHECK(expected[4] == 0.0);

    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            const uint64_t bytes = cases.size() * sizeof(Case);
            const BufferHandle buffer = device->createBuffer(
                {bytes, kBufferStorage | kBufferTransfer, MemoryAccess::GpuOnly, "form factor cases", "test"},
                cases.data());
            const ComputePipelineHandle pipeline = device->createPipeline(
                ComputePipelineDesc{&shaders::patch_form_factor_comp, "patch form factor"});
            CommandList& cmd = device->beginFrame();
            cmd.bindPipeline(pipeline);
            cmd.bindStorageBuffer(0, buffer, 0, bytes);
            cmd.dispatch(uint32_t(cases.size()));
            device->endFrame();
            device->waitIdle();
            std::vector<Case> out(cases.size());
            device->readBuffer(buffer, 0, out.data(), bytes);
            for (size_t i = 0; i < out.size(); ++i) {
                INFO("case " << i);
                CHECK(out[i].result.x == doctest::Approx(expected[i]).epsilon(2e-3).scale(1e-3));
                // The extents survive their packing into a VPL's position.w to a half's precision.
                CHECK(out[i].result.y == doctest::Approx(cases[i].receiver.w).epsilon(1e-3));
                CHECK(out[i].result.z == doctest::Approx(cases[i].normal.w).epsilon(1e-3));
            }
            // Where the gather switches to a point's kernel, the two agree within 2%.
            const double point = 0.25 / (3.14159265358979 * 2.5 * 2.5);
            CHECK(std::abs(out[5].result.x / point - 1.0) < 0.02);
            device->destroy(pipeline);
            device->destroy(buffer);
            device.expectSilent();
        }
    }
}
