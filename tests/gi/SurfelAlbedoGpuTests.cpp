// The albedo multiple bounces reflect with: a cell's is the mean of its surfels', however many
// crowd into it (gv_albedo_sums_body.glsl sums them in 16-bit fixed point per channel).
#include "../support/Image.h"
#include "../support/TestDevice.h"
#include "gi/GeometryVolume.h"

#include <doctest/doctest.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

struct GpuVpl {
    glm::vec4 position, normal, flux; // flux.w: its texel count
};

constexpr uint32_t kCells = 4;
constexpr float kCell = 0.5f;
// Two albedos, in runs of four surfels: a cell of both has their mean, and so does every fourth of
// them (the surfels taken where a cell could count more than the sums hold).
const glm::vec3 kAlbedoA(0.2f, 0.4f, 0.6f), kAlbedoB(0.8f, 0.6f, 0.25f);

// `count` VPLs at GV cell (1, 1, 1), the corner the LPV cells 0..1 per axis share: their albedo is
// their flux over a white texel's (1 here) times their texel count (1).
std::vector<GpuVpl> crowd(uint32_t count) {
    std::vector<GpuVpl> v;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 albedo = (i / 4) % 2 == 0 ? kAlbedoA : kAlbedoB;
        v.push_back({{kCell, kCell, kCell, 1.0f}, {0.0f, 1.0f, 0.0f, 1.0f}, glm::vec4(albedo, 1.0f)});
    }
    return v;
}

// Builds `geometry` from `src` in one frame and reads back its surfel albedo.
Image surfelAlbedo(rhi::Device& device, gi::GeometryVolume& geometry, const gi::GeometrySources& src) {
    rhi::CommandList& cmd = device.beginFrame();
    geometry.record(cmd, {{0.0f, 0.0f, 0.0f}, kCell, kCells}, src);
    device.endFrame();
    device.waitIdle();
    return readImage(device, geometry.surfelAlbedo());
}

struct AlbedoErrors {
    float worst = 0.0f;      // the largest error of a channel in a cell with surfels
    uint32_t wrongCells = 0; // cells with surfels but not their full weight, or without but not empty
};

// Each LPV cell's albedo against expected(x, y, z): its surfels' mean, or none where it has none.
template <typename Expected> AlbedoErrors albedoErrors(const Image& albedo, Expected&& expected) {
    AlbedoErrors e;
    for (uint32_t z = 0; z < kCells; ++z)
        for (uint32_t y = 0; y < kCells; ++y)
            for (uint32_t x = 0; x < kCells; ++x) {
                const glm::vec4 t = albedo.at(x, y, z);
                const std::optional<glm::vec3> mean = expected(x, y, z);
                if (!mean) {
                    e.wrongCells += t == glm::vec4(0.0f) ? 0 : 1;
                    continue;
                }
                for (int c = 0; c < 3; ++c)
                    e.worst = std::max(e.worst, std::abs(t[c] - (*mean)[c]));
                e.wrongCells += t.w == 1.0f ? 0 : 1;
            }
    return e;
}

} // namespace

TEST_CASE("gi: a cell's surfel albedo is the mean of its surfels', however many crowd into it") {
    const glm::vec3 mean = 0.5f * (kAlbedoA + kAlbedoB);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            gi::GeometryVolume geometry(*device, kCells, true);
            // 1,000 surfels; 30,000 (near the most a cell counts, each adding about 1 unit); and
            // 100,000 (every fourth taken).
            for (uint32_t count : {1000u, 30000u, 100000u}) {
                const std::vector<GpuVpl> vpls = crowd(count);
                const rhi::BufferHandle buffer = device->createBuffer(
                    {vpls.size() * sizeof(GpuVpl), rhi::kBufferStorage | rhi::kBufferTransfer,
                     rhi::MemoryAccess::GpuOnly, "test vpls", "test"},
                    vpls.data());
                gi::GeometrySources src;
                src.vpls = buffer;
                src.vplCount = count;
                src.vplArea = 0.01f;
                src.whiteTexelFlux = glm::vec3(1.0f);
                const Image albedo = surfelAlbedo(*device, geometry, src);
                // Every LPV cell with the crowded corner, and none other, has the mean; 0.01 is
                // the dither's error over so many surfels and the RGBA8 volume's rounding.
                const AlbedoErrors e = albedoErrors(albedo, [&](uint32_t x, uint32_t y, uint32_t z) {
                    return x < 2 && y < 2 && z < 2 ? std::optional(mean) : std::nullopt;
                });
                MESSAGE(backend.name << ": " << count << " surfels in a cell: largest error of the mean "
                                     << e.worst << ", corner cell " << describe(albedo.at(0, 0, 0)));
                CHECK(e.wrongCells == 0);
                CHECK(e.worst <= 0.01f);
                device->destroy(buffer);
            }
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: a spot light's surfels give their cells the albedo its RSM lit them with") {
    // A surface only a spot light sees (no camera, no sun) reflects in the further bounces with the
    // albedo its VPLs' flux holds: their flux over what a white block reflects there, the light's
    // intensity x cone x range window x the block's solid angle x cos^3 off the axis
    // (rsm_spot.frag). Without it such a surface had no albedo and reflected nothing.
    engine::Light spot;
    spot.type = engine::LightType::Spot;
    spot.position = glm::vec3(kCell, 3.0f * kCell, kCell);
    spot.color = glm::vec3(1.0f, 0.5f, 0.25f);
    spot.intensity = 40.0f;
    spot.range = 5.0f;
    spot.innerConeAngle = 0.2f;
    spot.outerConeAngle = 0.5f;
    gi::PointLightSurfels light;
    light.position = spot.position;
    light.axis = spot.direction;
    light.vplSolidAngle = 0.02f;
    light.light = gi::analyticLight(spot, 1.0f);
    const glm::vec3 intensity = spot.color * spot.intensity;
    const float cosOuter = std::cos(spot.outerConeAngle), cosInner = std::cos(spot.innerConeAngle);
    // One VPL on the axis at GV cell (1, 1, 1), one off it at (2, 1, 1), half of its block's
    // texels, where the cone falls off; and one outside the cone in that cell too, which says
    // nothing of the surface (counted, it would halve the cell's albedo).
    const glm::vec3 onAxis(kCell, kCell, kCell), offAxis(2.0f * kCell, kCell, kCell),
        outside(2.4f * kCell, kCell, 1.4f * kCell);
    const auto white = [&](glm::vec3 p, float share) {
        const glm::vec3 d = p - light.position;
        const float d2 = glm::dot(d, d);
        const float cosAxis = glm::dot(glm::normalize(d), light.axis);
        const float t = glm::clamp((cosAxis - cosOuter) / (cosInner - cosOuter), 0.0f, 1.0f);
        const float q = d2 / (spot.range * spot.range);
        return intensity * (t * t * (3.0f - 2.0f * t)) * (1.0f - q * q) * light.vplSolidAngle * share *
               cosAxis * cosAxis * cosAxis;
    };
    REQUIRE(glm::dot(glm::normalize(offAxis - light.position), light.axis) < cosInner);
    REQUIRE(glm::dot(glm::normalize(outside - light.position), light.axis) < cosOuter);
    const std::vector<GpuVpl> vpls = {
        {glm::vec4(onAxis, 1.0f), {0.0f, 1.0f, 0.0f, 1.0f}, glm::vec4(kAlbedoA * white(onAxis, 1.0f), 16.0f)},
        {glm::vec4(offAxis, 1.0f),
         {0.0f, 1.0f, 0.0f, 0.5f},
         glm::vec4(kAlbedoB * white(offAxis, 0.5f), 8.0f)},
        {glm::vec4(outside, 1.0f), {0.0f, 1.0f, 0.0f, 1.0f}, glm::vec4(0.0f, 0.0f, 0.0f, 16.0f)}};
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            gi::GeometryVolume geometry(*device, kCells, true);
            const rhi::BufferHandle buffer = device->createBuffer(
                {vpls.size() * sizeof(GpuVpl), rhi::kBufferStorage | rhi::kBufferTransfer,
                 rhi::MemoryAccess::GpuOnly, "test vpls", "test"},
                vpls.data());
            light.vpls = buffer;
            light.count = uint32_t(vpls.size());
            gi::GeometrySources src;
            src.pointLights = std::span(&light, 1);
            const Image albedo = surfelAlbedo(*device, geometry, src);
            // GV cell (1, 1, 1) is the corner of LPV cells 0..1, (2, 1, 1) of cells 1..2 along x.
            const AlbedoErrors e = albedoErrors(albedo, [&](uint32_t x, uint32_t y, uint32_t z) {
                const bool a = x < 2 && y < 2 && z < 2, b = x >= 1 && x < 3 && y < 2 && z < 2;
                if (!a && !b) return std::optional<glm::vec3>();
                return std::optional(a && b ? 0.5f * (kAlbedoA + kAlbedoB) : a ? kAlbedoA : kAlbedoB);
            });
            MESSAGE(backend.name << ": largest albedo error " << e.worst << ", cell (0, 0, 0) "
                                 << describe(albedo.at(0, 0, 0)) << ", (2, 0, 0) "
                                 << describe(albedo.at(2, 0, 0)));
            CHECK(e.wrongCells == 0);
            CHECK(e.worst <= 0.01f);
            device->destroy(buffer);
            device.expectSilent();
        }
    }
}
