// The gather's VPL windows (gi/VplWindows.h), on each backend: for a cluster grid whose side is no
// multiple of 4, each phase's list holds exactly the lit VPLs its window takes, in the grid's
// order (the gather sums them in it), and nothing where a window takes none.
#include "../support/TestDevice.h"
#include "GpuVpls.h"
#include "gi/VplWindows.h"

#include <doctest/doctest.h>
#include <glm/common.hpp>
#include <glm/vec4.hpp>

#include <optional>
#include <random>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

constexpr uint32_t kSide = 10;

// The boxes: a cascade of 8 cells over [0, 2]^3 and a finer one over [0.5, 1.5]^3.
const gi::VolumeGrid kWithin{glm::vec3(0.0f), 0.25f, 8};
const gi::VolumeGrid kBeyond{glm::vec3(0.5f), 0.125f, 8};

bool inside(const gi::VolumeGrid& g, glm::vec3 p) {
    const glm::vec3 hi = g.origin + g.cellSize * float(g.size);
    return glm::all(glm::greaterThanEqual(p, g.origin)) && glm::all(glm::lessThanEqual(p, hi));
}

// Whether p lies within a hundredth of a metre of a box's side, where the lists' margin may keep a
// VPL the gather's own test then leaves.
bool nearSide(const gi::VolumeGrid& g, glm::vec3 p) {
    const glm::vec3 hi = g.origin + g.cellSize * float(g.size);
    for (int k = 0; k < 3; ++k)
        if (std::abs(p[k] - g.origin[k]) < 0.01f || std::abs(p[k] - hi[k]) < 0.01f) return true;
    return false;
}

std::vector<GpuVpl> randomGrid() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> at(-0.5f, 2.5f);
    std::vector<GpuVpl> vpls(2 * kSide * kSide);
    for (GpuVpl& v : vpls) {
        glm::vec3 p;
        do
            p = glm::vec3(at(rng), at(rng), at(rng));
        while (nearSide(kWithin, p) || nearSide(kBeyond, p));
        // A quarter unlit (position.w 0), as the slots past a scene's edge.
        v.position = glm::vec4(p, rng() % 4 == 0 ? 0.0f : 1.0f);
        v.normal = glm::vec4(0, 1, 0, 1);
        v.flux = glm::vec4(1.0f);
    }
    return vpls;
}

// The slots of phase `phase` the window takes, in the grid's order.
std::vector<uint32_t> expectedList(const std::vector<GpuVpl>& vpls, uint32_t phase, int window,
                                   const std::optional<gi::VolumeGrid>& within,
                                   const std::optional<gi::VolumeGrid>& beyond) {
    std::vector<uint32_t> out;
    for (uint32_t y = phase / 4; y < kSide; y += 4)
        for (uint32_t x = phase % 4; x < kSide; x += 4)
            for (uint32_t layer = 0; layer < 2; ++layer) {
                const uint32_t slot = 2 * (y * kSide + x) + layer;
                const glm::vec4 p = vpls[slot].position;
                bool takes = p.w > 0.0f && (!within || inside(*within, glm::vec3(p)));
                if (window == 1) takes = takes && beyond && !inside(*beyond, glm::vec3(p));
                if (takes) out.push_back(slot);
            }
    return out;
}

} // namespace

TEST_CASE("gi: the gather's VPL windows list the lit VPLs each window takes, in order") {
    const std::vector<GpuVpl> vpls = randomGrid();
    struct Boxes {
        const char* name;
        std::optional<gi::VolumeGrid> within, beyond;
    };
    const Boxes cases[] = {{"a middle cascade", kWithin, kBeyond},
                           {"the coarsest gathered", std::nullopt, kBeyond},
                           {"the finest", kWithin, std::nullopt}};
    // The grid holds VPLs of every kind: in the middle cascade, window 1 takes some of window 0's.
    size_t windowSizes[2] = {0, 0};
    for (int window = 0; window < 2; ++window)
        for (uint32_t phase = 0; phase < gi::VplWindows::kPhases; ++phase)
            windowSizes[window] += expectedList(vpls, phase, window, kWithin, kBeyond).size();
    REQUIRE(windowSizes[1] > 0);
    REQUIRE(windowSizes[1] < windowSizes[0]);
    REQUIRE(windowSizes[0] < vpls.size());
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            const BufferHandle grid =
                device->createBuffer({vpls.size() * sizeof(GpuVpl), kBufferStorage | kBufferTransfer,
                                      MemoryAccess::GpuOnly, "window test vpls", "test"},
                                     vpls.data());
            const uint64_t bytes = gi::VplWindows::bytes(kSide);
            const BufferHandle lists =
                device->createBuffer({bytes, kBufferStorage | kBufferTransfer, MemoryAccess::GpuOnly,
                                      "window test lists", "test"});
            gi::VplWindows windows(*device);
            const uint32_t room = gi::VplWindows::room(kSide);
            for (const Boxes& b : cases) {
                INFO(b.name);
                CommandList& cmd = device->beginFrame();
                windows.record(cmd, grid, kSide, b.within, b.beyond, lists);
                device->endFrame();
                device->waitIdle();
                std::vector<uint32_t> out(bytes / 4);
                device->readBuffer(lists, 0, out.data(), bytes);
                for (int window = 0; window < 2; ++window)
                    for (uint32_t phase = 0; phase < gi::VplWindows::kPhases; ++phase) {
                        INFO("window " << window << ", phase " << phase);
                        const std::vector<uint32_t> expected =
                            expectedList(vpls, phase, window, b.within, b.beyond);
                        const uint32_t list = 16 * uint32_t(window) + phase;
                        REQUIRE(out[list] == expected.size());
                        const auto first = out.begin() + 32 + list * room;
                        CHECK(std::vector<uint32_t>(first, first + expected.size()) == expected);
                    }
            }
            device->destroy(lists);
            device->destroy(grid);
            device.expectSilent();
        }
    }
}
