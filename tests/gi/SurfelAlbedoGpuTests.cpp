// The albedo multiple bounces reflect with: a cell's is the mean of its surfels', however many
// crowd into it (gv_albedo_sums_body.glsl sums them in 16-bit fixed point per channel).
#include "../support/Image.h"
#include "../support/TestDevice.h"
#include "gi/GeometryVolume.h"

#include <doctest/doctest.h>
#include <glm/vec4.hpp>

#include <cmath>
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
                rhi::CommandList& cmd = device->beginFrame();
                geometry.record(cmd, {{0.0f, 0.0f, 0.0f}, kCell, kCells}, src);
                device->endFrame();
                device->waitIdle();
                const Image albedo = readImage(*device, geometry.surfelAlbedo());
                // Every LPV cell with the crowded corner, and none other, has the mean; 0.01 is
                // the dither's error over so many surfels and the RGBA8 volume's rounding.
                float worst = 0.0f;
                uint32_t wrongCells = 0;
                for (uint32_t z = 0; z < kCells; ++z)
                    for (uint32_t y = 0; y < kCells; ++y)
                        for (uint32_t x = 0; x < kCells; ++x) {
                            const glm::vec4 t = albedo.at(x, y, z);
                            if (x < 2 && y < 2 && z < 2) {
                                for (int c = 0; c < 3; ++c)
                                    worst = std::max(worst, std::abs(t[c] - mean[c]));
                                wrongCells += t.w == 1.0f ? 0 : 1;
                            } else {
                                wrongCells += t == glm::vec4(0.0f) ? 0 : 1;
                            }
                        }
                MESSAGE(backend.name << ": " << count << " surfels in a cell: largest error of the mean "
                                     << worst << ", corner cell " << describe(albedo.at(0, 0, 0)));
                CHECK(wrongCells == 0);
                CHECK(worst <= 0.01f);
                device->destroy(buffer);
            }
            device.expectSilent();
        }
    }
}
