// Occlusion on each backend: a thin wall between a lit area and a dark room. The wall's surfels go
// into the geometry volume, from the sun's RSM or from a point light's; with occlusion the light
// that reaches the room must be at most 10% of what reaches it without.
#include "../support/Image.h"
#include "../support/TestDevice.h"
#include "GpuVpls.h"
#include "gi/GeometryVolume.h"
#include "gi/LpvInjection.h"
#include "gi/LpvPropagation.h"
#include "gi/LpvVolumes.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

// 16^3 cells of 0.5 m from the origin. The wall is the plane x = 4 m (between cells 7 and 8),
// across the whole volume; the lit area is the floor strip x in 0.5 .. 3.5 m; the room is x >= 4.5 m.
constexpr uint32_t kCells = 16;
constexpr float kCell = 0.5f, kWallX = 4.0f, kSpacing = 0.25f;

std::vector<GpuVpl> scene() {
    std::vector<GpuVpl> v;
    // Lit floor: bright VPLs facing up.
    for (float x = 0.5f; x <= 3.5f; x += kSpacing)
        for (float z = 0.25f; z < 8.0f; z += kSpacing)
            v.push_back({{x, 0.3f, z, 1}, {0, 1, 0, 1}, {0.05f, 0.05f, 0.05f, 0}});
    // The wall's lit face, facing the lit area: reflects a little and, as a surfel, blocks.
    for (float y = 0.125f; y < 8.0f; y += kSpacing)
        for (float z = 0.125f; z < 8.0f; z += kSpacing)
            v.push_back({{kWallX - 0.01f, y, z, 1}, {-1, 0, 0, 1}, {0.01f, 0.01f, 0.01f, 0}});
    return v;
}

// The light in the room: the L0 coefficients of every room cell, all channels.
float roomLight(rhi::Device& device, const gi::LpvVolumes& volumes) {
    float sum = 0.0f;
    for (int ch = 0; ch < 3; ++ch) {
        const Image img = readImage(device, volumes.accumulated()[size_t(ch)]);
        for (uint32_t z = 0; z < kCells; ++z)
            for (uint32_t y = 0; y < kCells; ++y)
                for (uint32_t x = 9; x < kCells; ++x) // cell 9 starts at 4.5 m
                    sum += std::max(0.0f, img.at(x, y, z).x);
    }
    return sum;
}

rhi::BufferHandle upload(rhi::Device& device, const std::vector<GpuVpl>& vpls) {
    return device.createBuffer({vpls.size() * sizeof(GpuVpl), rhi::kBufferStorage | rhi::kBufferTransfer,
                                rhi::MemoryAccess::GpuOnly, "test vpls", "test"},
                               vpls.data());
}

// The scene's light (`light`, its VPLs travelling along `direction`) propagated 8 times through
// the geometry volume built from `surfels`, in volumes made with `settings`, without occlusion and
// with it.
struct WallRun {
    float open = 0.0f, walled = 0.0f;
    float wallCoverage = 0.0f; // of the faces in the wall's plane, away from the volume's edges
    Image faces;               // face transmittance
};
WallRun runWall(rhi::Device& device, const gi::LpvSettings& settings, gi::GeometryVolume& geometry,
                rhi::BufferHandle light, uint32_t count, glm::vec3 direction,
                const gi::GeometrySources& surfels) {
    const gi::VolumeGrid grid{{0.0f, 0.0f, 0.0f}, kCell, kCells};
    gi::LpvVolumes volumes(device, settings);
    gi::LpvInjection injection(device, settings);
    gi::LpvPropagation propagation(device, settings);
    WallRun run;
    for (bool occlusion : {false, true}) {
        rhi::CommandList& cmd = device.beginFrame();
        geometry.record(cmd, grid, surfels);
        injection.record(cmd, volumes, light, count, grid, direction, 1.0f);
        propagation.record(cmd, volumes, 8, occlusion ? geometry.faceTransmittance() : rhi::TextureHandle{});
        device.endFrame();
        device.waitIdle();
        (occlusion ? run.walled : run.open) = roomLight(device, volumes);
    }
    // The wall's plane: cell 8's -x faces.
    run.faces = readImage(device, geometry.faceTransmittance());
    for (uint32_t z = 1; z + 1 < kCells; ++z)
        for (uint32_t y = 1; y + 1 < kCells; ++y)
            run.wallCoverage += 1.0f - run.faces.at(8, y, z).x;
    run.wallCoverage /= float((kCells - 2) * (kCells - 2));
    return run;
}

} // namespace

TEST_CASE("gi: a thin wall keeps the light of a lit area out of a dark room (occlusion)") {
    const std::vector<GpuVpl> vpls = scene();
    const glm::vec3 light = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    // One cascade (bounded partial sums, as on the Xbox 360) and several (partial sums with a
    // shell): both occluded propagation kernels.
    for (const auto& backend : selectedBackends())
        for (const uint32_t cascades : {1u, 3u}) {
            SUBCASE((backend.name + ", " + std::to_string(cascades) + " cascades").c_str()) {
                TestDevice device(backend);
                gi::LpvSettings s;
                s.gridSize = kCells;
                s.cascades = cascades;
                s.shFormat = gi::ShFormat::Rgba32f;
                const rhi::BufferHandle buffer = upload(*device, vpls);
                WallRun run;
                {
                    gi::GeometryVolume geometry(*device, kCells, false);
                    gi::GeometrySources src;
                    src.vpls = buffer;
                    src.vplCount = uint32_t(vpls.size());
                    // Every surfel stands for kSpacing^2 of surface; the wall faces the light's x.
                    src.vplArea = kSpacing * kSpacing * std::abs(glm::dot(light, glm::vec3(1, 0, 0)));
                    src.lightDirection = light;
                    run = runWall(*device, s, geometry, buffer, uint32_t(vpls.size()), light, src);
                }
                // Faces elsewhere are open (the floor surfels only cover faces along y).
                CHECK(run.faces.at(4, 5, 5).x == doctest::Approx(1.0f));
                CHECK(run.faces.at(12, 5, 5).x == doctest::Approx(1.0f));
                MESSAGE(backend.name << ", " << cascades << " cascades: light in the room without occlusion "
                                     << run.open << ", with " << run.walled << " ("
                                     << 100.0f * run.walled / run.open << "%); wall faces covered "
                                     << run.wallCoverage);
                REQUIRE(run.open > 0.0f);
                CHECK(run.wallCoverage > 0.9f);
                CHECK(run.walled <= 0.10f * run.open);
                device->destroy(buffer);
                device.expectSilent();
            }
        }
}

TEST_CASE("gi: the surfels of a spot or point light's RSM block like the sun's (occlusion)") {
    // The same wall, seen this time only by a light at a point 3 m in front of it (a perspective
    // RSM looking +x): its VPLs are the wall's surfels. A block of texels of solid angle h^2 / D^2
    // on the axis covers h^2 of a plane D away across the axis, wherever on the plane, so the wall's
    // VPL grid of spacing h covers it as the sun's surfels do. The sun adds no surfels here.
    const std::vector<GpuVpl> vpls = scene();
    std::vector<GpuVpl> wall;
    for (const GpuVpl& v : vpls)
        if (v.normal.x < 0.0f) wall.push_back(v);
    const glm::vec3 sunLight = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
    const glm::vec3 pointLight(1.0f, 4.0f, 4.0f);
    const float distance = (kWallX - 0.01f) - pointLight.x;
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            gi::LpvSettings s;
            s.gridSize = kCells;
            s.cascades = 1;
            s.shFormat = gi::ShFormat::Rgba32f;
            const rhi::BufferHandle light = upload(*device, vpls), surfels = upload(*device, wall);
            WallRun run;
            {
                gi::GeometryVolume geometry(*device, kCells, true);
                const gi::PointLightSurfels point{surfels,
                                                  uint32_t(wall.size()),
                                                  pointLight,
                                                  {1.0f, 0.0f, 0.0f},
                                                  kSpacing * kSpacing / (distance * distance)};
                gi::GeometrySources src;
                src.pointLights = std::span(&point, 1);
                run = runWall(*device, s, geometry, light, uint32_t(vpls.size()), sunLight, src);
            }
            CHECK(run.faces.at(4, 5, 5).x == doctest::Approx(1.0f));
            MESSAGE(backend.name << ": light in the room without occlusion " << run.open
                                 << ", with the point light's surfels " << run.walled << " ("
                                 << 100.0f * run.walled / run.open << "%); wall faces covered "
                                 << run.wallCoverage);
            REQUIRE(run.open > 0.0f);
            CHECK(run.wallCoverage > 0.9f);
            CHECK(run.walled <= 0.10f * run.open);
            device->destroy(light);
            device->destroy(surfels);
            device.expectSilent();
        }
    }
}
