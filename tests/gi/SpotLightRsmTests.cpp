// Spot and point lights with their own RSM on the CPU (gi/SpotLightRsms.h,
// gi/ReflectiveShadowMap.h): the perspective fit holds the whole cone and no more than it needs, its
// depth range follows the range and the volume, a point light's six cube faces tile the sphere, the
// choice of lights, the cascades each light's VPLs go to, and the budget counts their memory.
#include "../support/TestDevice.h"

#include "gi/GiBudget.h"
#include "gi/ReflectiveShadowMap.h"
#include "gi/SpotLightRsms.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

using namespace lpv;
using namespace lpv::gi;

namespace {

engine::Light spotLight(glm::vec3 position, glm::vec3 direction, float outer, float intensity = 1.0f,
                        float range = 0.0f) {
    engine::Light l;
    l.type = engine::LightType::Spot;
    l.position = position;
    l.direction = glm::normalize(direction);
    l.outerConeAngle = outer;
    l.innerConeAngle = 0.5f * outer;
    l.intensity = intensity;
    l.range = range;
    return l;
}

// Two unit vectors perpendicular to `axis` and to each other.
void basis(glm::vec3 axis, glm::vec3& u, glm::vec3& v) {
    u = glm::normalize(glm::cross(axis, std::fabs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    v = glm::cross(axis, u);
}

} // namespace

TEST_CASE("spot rsm: the perspective fit holds the whole cone, and tightly") {
    const engine::Light spots[] = {
        spotLight({1.0f, 3.0f, -2.0f}, {0.3f, -1.0f, 0.2f}, 0.2f, 1.0f, 6.0f),
        spotLight({0.0f, 4.0f, 0.0f}, {0.0f, -1.0f, 0.0f}, 0.785398f), // straight down: the other up vector
        spotLight({-2.0f, 1.0f, 5.0f}, {1.0f, 0.2f, -1.0f}, 1.0f, 1.0f, 20.0f),
        spotLight({0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, 1.5f), // wider than a perspective map holds
    };
    const float reach = 12.0f;
    for (const engine::Light& spot : spots) {
        CAPTURE(spot.outerConeAngle);
        const SpotRsmFit fit = fitSpotRsm(spot, reach);
        CHECK(fit.farPlane == doctest::Approx(spot.range > 0.0f ? std::min(spot.range, reach) : reach));
        CHECK(fit.nearPlane > 0.0f);
        CHECK(fit.nearPlane < 0.01f * fit.farPlane + 0.02f);
        const float half = std::min(spot.outerConeAngle, kMaxSpotRsmHalfAngle);
        glm::vec3 u, v;
        basis(spot.direction, u, v);
        // Rays on the cone's rim, from just past the near plane to just before the far one.
        float widest = 0.0f;
        bool inside = true;
        for (int a = 0; a < 64; ++a) {
            const float phi = 2.0f * 3.14159265f * float(a) / 64.0f;
            const glm::vec3 rim =
                std::cos(half) * spot.direction + std::sin(half) * (std::cos(phi) * u + std::sin(phi) * v);
            for (float t : {1.01f * fit.nearPlane / std::cos(half), 1.0f, 0.99f * fit.farPlane}) {
                const glm::vec4 clip = fit.viewProjection * glm::vec4(spot.position + t * rim, 1.0f);
                const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                inside = inside && clip.w > 0.0f && std::fabs(ndc.x) <= 1.0f && std::fabs(ndc.y) <= 1.0f &&
                         ndc.z >= 0.0f && ndc.z <= 1.0f;
                widest = std::max({widest, std::fabs(ndc.x), std::fabs(ndc.y)});
            }
        }
        CHECK(inside);
        // Tight: the rim touches the frustum's sides (the 1% margin), so no texel is wasted.
        CHECK(widest > 0.98f);
        // The axis is the frustum's centre; beyond the far plane is outside.
        const glm::vec4 centre = fit.viewProjection * glm::vec4(spot.position + spot.direction * 2.0f, 1.0f);
        CHECK(std::fabs(centre.x / centre.w) < 1e-4f);
        CHECK(std::fabs(centre.y / centre.w) < 1e-4f);
        const glm::vec4 beyond =
            fit.viewProjection * glm::vec4(spot.position + spot.direction * (1.02f * fit.farPlane), 1.0f);
        CHECK(beyond.z / beyond.w > 1.0f);
    }
}

TEST_CASE("spot rsm: the lights that matter most to the volume are chosen, in a stable order") {
    const VolumeGrid grid{{0.0f, 0.0f, 0.0f}, 0.5f, 16}; // [0, 8] m
    std::vector<engine::Light> lights;
    engine::Light point = spotLight({4, 4, 4}, {0, -1, 0}, 0.5f, 100.0f);
    point.type = engine::LightType::Point; // bright, but a point light: never chosen
    lights.push_back(point);
    lights.push_back(spotLight({4, 6, 4}, {0, -1, 0}, 0.5f, 2.0f));        // 1: dim, inside
    lights.push_back(spotLight({2, 6, 2}, {0, -1, 0}, 0.5f, 8.0f));        // 2: bright, inside
    lights.push_back(spotLight({-9, 4, 4}, {1, 0, 0}, 0.5f, 50.0f, 3.0f)); // 3: out of range
    lights.push_back(spotLight({6, 6, 6}, {0, -1, 0}, 0.5f, 8.0f));        // 4: ties with 2
    lights.push_back(spotLight({4, 40, 4}, {0, -1, 0}, 0.5f, 40.0f));      // 5: bright, far away
    engine::Light dark = spotLight({4, 2, 4}, {0, -1, 0}, 0.5f, 0.0f);     // 6: dark
    lights.push_back(dark);

    std::array<uint32_t, 4> out{};
    REQUIRE(selectRsmLights(lights, engine::LightType::Spot, grid, std::span(out.data(), 2)) == 2);
    CHECK(out[0] == 2); // the earlier of the two equally bright lights first
    CHECK(out[1] == 4);
    REQUIRE(selectRsmLights(lights, engine::LightType::Spot, grid, out) == 4);
    CHECK(out[2] == 1);
    // 40 over (40 - 4)^2 m^2 is less than 2 over the volume's half-extent squared.
    CHECK(out[3] == 5);
    CHECK(selectRsmLights(lights, engine::LightType::Spot, grid, std::span(out.data(), 0)) == 0);
    CHECK(selectRsmLights(std::span(lights.data(), 1), engine::LightType::Spot, grid, out) == 0);
}

TEST_CASE("spot rsm: the GI budget counts every spot light's RSM and VPLs") {
    LpvSettings s;
    s.lightRsms = 0;
    s.pointLightRsms = 0;
    const uint64_t none = giBytes(giResources(s));
    s.lightRsms = 2;
    const auto resources = giResources(s);
    // A quarter of the sun's VPL blocks: 256^2 texels in blocks of 8x8, two VPL slots each.
    CHECK(spotLightVplCount(s) == s.vplCount / 4);
    CHECK(spotLightVplSlots(s) == s.vplCount / 4 * kVplsPerCluster);
    const uint64_t perLight =
        uint64_t(s.rsmSize) * s.rsmSize * (4 + 8 + 8) + uint64_t(s.vplCount / 4) * kVplsPerCluster * 48;
    CHECK(giBytes(resources) == none + 2 * perLight);
    CHECK(std::count_if(resources.begin(), resources.end(), [](const GiResource& r) {
              return r.name.find("spot light 1") != std::string::npos;
          }) == 2);
}

TEST_CASE("spot rsm: a cascade gets the VPLs of the spot lights that reach it, and no others") {
    auto device = test::nullDevice();
    LpvSettings s;
    s.lightRsms = 3;
    SpotLightRsms rsms(*device, s);
    const VolumeGrid coarse{{-16.0f, -16.0f, -16.0f}, 1.0f, 32}, fine{{-4.0f, -4.0f, -4.0f}, 0.25f, 32};
    const std::vector<engine::Light> lights = {
        spotLight({0, 2, 0}, {0, -1, 0}, 0.5f, 4.0f, 3.0f),   // in both
        spotLight({10, 2, 0}, {0, -1, 0}, 0.5f, 4.0f, 3.0f),  // 6 m from the fine volume, range 3
        spotLight({-12, 2, 0}, {1, 0, 0}, 0.5f, 4.0f, 0.0f)}; // infinite range: everywhere
    rsms.select(lights, coarse);
    REQUIRE(rsms.selection().size() == 3);
    REQUIRE(rsms.sources().size() == 3);
    std::array<VplSource, SpotLightRsms::kMaxLights> out{};
    CHECK(rsms.sourcesReaching(coarse, out) == 3);
    REQUIRE(rsms.sourcesReaching(fine, out) == 2);
    CHECK(out[0].light == glm::vec4(lights[0].position, 1.0f));
    CHECK(out[1].light == glm::vec4(lights[2].position, 1.0f));
    for (const VplSource& v : rsms.sources()) {
        CHECK(v.vpls);
        CHECK(v.count == s.vplCount / 4 * kVplsPerCluster);
    }
    CHECK(rsms.sourcesReaching(fine, std::span(out.data(), 1)) == 1);
}

TEST_CASE("point rsm: a cascade gets the VPLs of the cube faces that see it, and no others") {
    auto device = test::nullDevice();
    LpvSettings s;
    s.lightRsms = 0;
    s.pointLightRsms = 1;
    SpotLightRsms rsms(*device, s);
    const VolumeGrid coarse{{-16.0f, -16.0f, -16.0f}, 1.0f, 32}, fine{{-4.0f, -4.0f, -4.0f}, 0.25f, 32};
    engine::Light point;
    point.type = engine::LightType::Point;
    point.position = {12.0f, 0.0f, 0.0f}; // inside the coarse volume, 8 m along +x from the fine one
    const std::vector<engine::Light> lights = {point};
    rsms.select(lights, coarse);
    REQUIRE(rsms.rsmCount() == kCubeFaces);
    std::array<VplSource, SpotLightRsms::kMaxRsms> out{};
    // Every face sees part of the volume around the light ...
    CHECK(rsms.sourcesReaching(coarse, out) == kCubeFaces);
    // ... only the -x face the fine volume: the +y face's pyramid, say, holds only points whose y
    // exceeds their distance from the light along x (at least 8 m there), and the fine volume's y
    // stays within 4 m.
    REQUIRE(rsms.sourcesReaching(fine, out) == 1);
    CHECK(out[0].vpls == rsms.sources()[1].vpls); // faces +x, -x, +y, -y, +z, -z
}

TEST_CASE("point rsm: a point light's six cube faces tile the sphere") {
    engine::Light point;
    point.type = engine::LightType::Point;
    point.position = {1.0f, 2.0f, -3.0f};
    // Directions spread over the sphere (a Fibonacci spiral): each lands inside exactly one face.
    const int n = 2000;
    int once = 0;
    for (int i = 0; i < n; ++i) {
        const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
        const float r = std::sqrt(1.0f - z * z), phi = 2.39996323f * float(i);
        const glm::vec3 d(r * std::cos(phi), r * std::sin(phi), z);
        int faces = 0;
        for (uint32_t f = 0; f < kCubeFaces; ++f) {
            const SpotRsmFit fit = fitCubeFace(point, f, 10.0f);
            const glm::vec4 c = fit.viewProjection * glm::vec4(point.position + 5.0f * d, 1.0f);
            if (std::fabs(c.x) <= c.w && std::fabs(c.y) <= c.w && c.z >= 0.0f && c.z <= c.w) ++faces;
        }
        once += faces == 1 ? 1 : 0;
    }
    CHECK(once == n);
    // Exactly 90 degrees, so the faces meet without overlap (the GPU test sums the faces' flux to
    // albedo x I x 4 pi).
    for (uint32_t f = 0; f < kCubeFaces; ++f)
        CHECK(fitCubeFace(point, f, 10.0f).tanHalfAngle == 1.0f);
}

TEST_CASE("point rsm: the GI budget counts a point light's six RSMs and VPL buffers") {
    LpvSettings s;
    s.lightRsms = 0;
    s.pointLightRsms = 0;
    const uint64_t none = giBytes(giResources(s));
    s.pointLightRsms = 2;
    const uint64_t perFace =
        uint64_t(s.rsmSize) * s.rsmSize * (4 + 8 + 8) + uint64_t(spotLightVplSlots(s)) * 48;
    CHECK(giBytes(giResources(s)) == none + 2 * kCubeFaces * perFace);
    // 7.8 MiB for one point light at the defaults (RSM 256, 4096 VPLs): the PC's 64 MiB hold it,
    // the consoles' 3 MiB do not.
    s.pointLightRsms = 1;
    CHECK(giBytes(giResources(s)) - none == kCubeFaces * perFace);
    CHECK(kCubeFaces * perFace > (7ull << 20));
}
