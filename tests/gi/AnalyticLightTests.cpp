// The analytic point and spot lights on the CPU (gi/AnalyticLight.h): the units against a VPL of
// the same flux, the fall-off, range, cone, the light's own cell, and which lights reach a volume.
#include "gi/AnalyticLight.h"
#include "gi/ShBasis.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <cmath>

using namespace lpv;
using namespace lpv::gi;

namespace {

const VolumeGrid kGrid{{0.0f, 0.0f, 0.0f}, 0.5f, 16};

glm::vec3 centreOf(glm::ivec3 cell) {
    return kGrid.origin + (glm::vec3(cell) + 0.5f) * kGrid.cellSize;
}

engine::Light pointLight(glm::vec3 position, glm::vec3 color, float intensity, float range = 0.0f) {
    engine::Light l;
    l.type = engine::LightType::Point;
    l.position = position;
    l.color = color;
    l.intensity = intensity;
    l.range = range;
    return l;
}

void checkCellsEqual(const ShCell& a, const ShCell& b) {
    for (int k = 0; k < 4; ++k) {
        CHECK(a.r[k] == doctest::Approx(b.r[k]).epsilon(1e-5));
        CHECK(a.g[k] == doctest::Approx(b.g[k]).epsilon(1e-5));
        CHECK(a.b[k] == doctest::Approx(b.b[k]).epsilon(1e-5));
    }
}

} // namespace

TEST_CASE("gi reference: an analytic light's cell holds what a VPL of the same flux injects") {
    const glm::vec3 p(2.1f, 3.3f, 4.2f);
    const AnalyticLight light = analyticLight(pointLight(p, {1.0f, 0.5f, 0.25f}, 2.0f), 1.0f);
    for (const glm::ivec3 cell : {glm::ivec3(9, 6, 8), glm::ivec3(4, 12, 1), glm::ivec3(4, 6, 9)}) {
        const glm::vec3 toCell = centreOf(cell) - p;
        const float d2 = glm::dot(toCell, toCell);
        const glm::vec3 w = glm::normalize(toCell);
        // The flux through the cell's cross-section: I x s^2 / d^2 per channel.
        const glm::vec3 flux = glm::vec3(2.0f, 1.0f, 0.5f) * (kGrid.cellSize * kGrid.cellSize / d2);
        const ShCell c = analyticLightCell(light, kGrid, cell);
        // The L0 coefficient carries the flux exactly as for a VPL (2 sqrt(pi) c0 = watts) ...
        CHECK(4.0f * kPi * kShY0 * c.r.x == doctest::Approx(flux.r).epsilon(1e-5));
        CHECK(4.0f * kPi * kShY0 * c.b.x == doctest::Approx(flux.b).epsilon(1e-5));
        // ... and the whole cell is the VPL of that flux facing w, injected into that cell (light
        // direction = normal: no half-cell shift, it lands in the cell it sits in).
        ShVolume volume(kGrid.size);
        injectReference(volume, kGrid, {{centreOf(cell), w, flux}}, w);
        checkCellsEqual(c, volume.at(uint32_t(cell.x), uint32_t(cell.y), uint32_t(cell.z)));
    }
}

TEST_CASE("gi reference: an analytic light falls off as 1/d^2 and lights a facing surface by 0.583 I/d^2") {
    const glm::vec3 p = centreOf({3, 8, 8}); // a light at a cell centre, cells along +x
    const AnalyticLight light = analyticLight(pointLight(p, {1.0f, 1.0f, 1.0f}, 3.0f), 1.0f);
    const ShCell at2 = analyticLightCell(light, kGrid, {5, 8, 8}),
                 at4 = analyticLightCell(light, kGrid, {7, 8, 8});
    CHECK(at4.r.x == doctest::Approx(at2.r.x / 4.0f));
    CHECK(at4.r.w == doctest::Approx(at2.r.w / 4.0f));
    CHECK(at2.r.y == 0.0f); // travelling along +x: only the x coefficient (index 3) of L1
    // The lookup's irradiance (SH against the cosine lobe, over the cell's cross-section) on a
    // surface facing the light: (c0^2 + c1^2) / pi of the exact I / d^2, the L1 cosine-lobe blur.
    const float d = 2.0f * kGrid.cellSize, s2 = kGrid.cellSize * kGrid.cellSize;
    const float facing = shIrradiance(at2.r, {1.0f, 0.0f, 0.0f}) / s2;
    CHECK(facing == doctest::Approx(0.5833333f * 3.0f / (d * d)).epsilon(1e-4));
    // Edge-on: 0.25 of it; facing away: nothing that survives the lookup's clamp.
    CHECK(shIrradiance(at2.r, {0.0f, 1.0f, 0.0f}) / s2 ==
          doctest::Approx(0.25f * 3.0f / (d * d)).epsilon(1e-4));
    CHECK(shIrradiance(at2.r, {-1.0f, 0.0f, 0.0f}) < 0.0f);
}

TEST_CASE("gi reference: analytic light range window, spot cone and gi.intensity") {
    const glm::vec3 p = centreOf({8, 8, 8});
    // Range 2 m: the renderer's window 1 - (d / range)^4, nothing at or beyond the range.
    const AnalyticLight ranged = analyticLight(pointLight(p, glm::vec3(1.0f), 1.0f, 2.0f), 1.0f);
    const AnalyticLight infinite = analyticLight(pointLight(p, glm::vec3(1.0f), 1.0f), 1.0f);
    const ShCell near = analyticLightCell(ranged, kGrid, {10, 8, 8}); // d = 1 m
    CHECK(near.r.x ==
          doctest::Approx((1.0f - 1.0f / 16.0f) * analyticLightCell(infinite, kGrid, {10, 8, 8}).r.x));
    CHECK(analyticLightCell(ranged, kGrid, {12, 8, 8}).r.x == 0.0f); // d = 2 m
    CHECK(analyticLightCell(ranged, kGrid, {15, 8, 8}).r.x == 0.0f);
    CHECK(analyticLightCell(infinite, kGrid, {15, 8, 8}).r.x > 0.0f);

    // A spot pointing down with a 0.3 rad inner and 0.5 rad outer cone.
    engine::Light spot = pointLight(p, glm::vec3(1.0f), 1.0f);
    spot.type = engine::LightType::Spot;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.innerConeAngle = 0.3f;
    spot.outerConeAngle = 0.5f;
    const AnalyticLight s = analyticLight(spot, 1.0f);
    checkCellsEqual(analyticLightCell(s, kGrid, {8, 3, 8}), analyticLightCell(infinite, kGrid, {8, 3, 8}));
    CHECK(analyticLightCell(s, kGrid, {8, 13, 8}).r.x == 0.0f); // above the light
    CHECK(analyticLightCell(s, kGrid, {13, 3, 8}).r.x == 0.0f); // 45 degrees off the axis
    // Between the cones: atan(2 / 4) = 0.46 rad off the axis.
    const float partial = analyticLightCell(s, kGrid, {10, 4, 8}).r.x;
    CHECK(partial > 0.0f);
    CHECK(partial < analyticLightCell(infinite, kGrid, {10, 4, 8}).r.x);
    // A hard-edged cone still gets a falloff band smoothstep can evaluate.
    spot.innerConeAngle = spot.outerConeAngle;
    const AnalyticLight hard = analyticLight(spot, 1.0f);
    CHECK(hard.spotCos.w > hard.intensityCos.w);

    // gi.intensity scales the light, as it scales the VPLs.
    const AnalyticLight doubled = analyticLight(pointLight(p, glm::vec3(1.0f), 1.0f), 2.0f);
    CHECK(analyticLightCell(doubled, kGrid, {10, 8, 8}).g.x ==
          doctest::Approx(2.0f * analyticLightCell(infinite, kGrid, {10, 8, 8}).g.x));
}

TEST_CASE("gi reference: an analytic light skips its own cell and stays bounded next to it") {
    // Lights anywhere in cell (5, 5, 5), including near its faces and corners.
    for (const glm::vec3 offset : {glm::vec3(0.5f), glm::vec3(0.01f, 0.5f, 0.5f),
                                   glm::vec3(0.99f, 0.98f, 0.97f), glm::vec3(0.02f, 0.99f, 0.5f)}) {
        const glm::vec3 p = kGrid.origin + (glm::vec3(5.0f) + offset) * kGrid.cellSize;
        const AnalyticLight light = analyticLight(pointLight(p, glm::vec3(1.0f), 1.0f), 1.0f);
        const ShCell own = analyticLightCell(light, kGrid, {5, 5, 5});
        CHECK(own.r == glm::vec4(0.0f));
        // Every other cell's centre is at least half a cell away: at most 4 sr of the light's
        // intensity crosses it, so L0 <= 4 / (2 sqrt(pi)).
        for (int z = 3; z <= 7; ++z)
            for (int y = 3; y <= 7; ++y)
                for (int x = 3; x <= 7; ++x) {
                    const ShCell c = analyticLightCell(light, kGrid, {x, y, z});
                    REQUIRE(std::isfinite(c.r.x));
                    REQUIRE(4.0f * kPi * kShY0 * c.r.x <= 4.0f + 1e-4f);
                }
    }
}

TEST_CASE("gi reference: which analytic lights reach the volume") {
    // The volume spans [0, 8] m on every axis.
    CHECK(reachesVolume(analyticLight(pointLight({4, 4, 4}, glm::vec3(1.0f), 1.0f, 1.0f), 1.0f), kGrid));
    CHECK(reachesVolume(analyticLight(pointLight({-0.5f, 4, 4}, glm::vec3(1.0f), 1.0f, 1.0f), 1.0f), kGrid));
    CHECK_FALSE(
        reachesVolume(analyticLight(pointLight({-1.5f, 4, 4}, glm::vec3(1.0f), 1.0f, 1.0f), 1.0f), kGrid));
    CHECK_FALSE(
        reachesVolume(analyticLight(pointLight({9, 9, 9}, glm::vec3(1.0f), 1.0f, 1.7f), 1.0f), kGrid));
    CHECK(reachesVolume(analyticLight(pointLight({9, 9, 9}, glm::vec3(1.0f), 1.0f, 1.8f), 1.0f), kGrid));
    CHECK(reachesVolume(analyticLight(pointLight({-50, 4, 4}, glm::vec3(1.0f), 1.0f), 1.0f),
                        kGrid)); // infinite
    CHECK_FALSE(reachesVolume(analyticLight(pointLight({4, 4, 4}, glm::vec3(0.0f), 1.0f), 1.0f), kGrid));
    CHECK_FALSE(reachesVolume(analyticLight(pointLight({4, 4, 4}, glm::vec3(1.0f), 1.0f), 0.0f), kGrid));
}
