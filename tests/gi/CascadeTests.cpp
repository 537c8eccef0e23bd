// Cascades on each backend, read back from the GPU volumes of Cornell box frames: the irradiance
// of a static scene does not move when the camera moves by less than a cell, the lookup's blend
// between cascades is continuous across a cascade's border, and a coarse cascade updated in two
// halves on two frames (the budget scheduler's split) holds what a whole update gives.
#include "../render/CornellFrame.h"
#include "../support/RoomOnGround.h"
#include "../support/TestDevice.h"

#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/LightPropagationVolume.h"
#include "gi/LpvPropagation.h"
#include "gi/ShBasis.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

const std::vector<std::string> kGi = {"gi.enabled=true", "gi.cell_size=0.17", "render.ssao=false",
                                      "gi.sh_format=rgba32f"};

// Trilinear SH of one channel at p (cell-centred samples, clamped to the volume).
glm::vec4 sampleSh(const Image& img, const gi::VolumeGrid& g, glm::vec3 p) {
    const glm::vec3 t = (p - g.origin) / g.cellSize - 0.5f;
    const glm::ivec3 base = glm::ivec3(glm::floor(t));
    const glm::vec3 f = t - glm::vec3(base);
    glm::vec4 sum(0.0f);
    for (int k = 0; k < 8; ++k) {
        const glm::ivec3 o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
        const glm::ivec3 c = glm::clamp(base + o, glm::ivec3(0), glm::ivec3(int(g.size) - 1));
        const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(o));
        sum += img.at(uint32_t(c.x), uint32_t(c.y), uint32_t(c.z)) * (w.x * w.y * w.z);
    }
    return sum;
}

// Cascade c's irradiance (luminance) at surface point p with normal n, as the lookup computes it
// (half a cell out along n, without damping).
float irradiance(const CornellFrame& f, size_t c, glm::vec3 p, glm::vec3 n) {
    const gi::VolumeGrid& g = f.cascadeGrids[c];
    const glm::vec3 q = p + 0.5f * g.cellSize * n;
    const glm::vec4 lobe = gi::shCosineLobe(-n);
    const float scale = 1.0f / (g.cellSize * g.cellSize);
    const float r = std::max(0.0f, glm::dot(sampleSh(f.cascadeVolumes[c][0], g, q), lobe)) * scale;
    const float gr = std::max(0.0f, glm::dot(sampleSh(f.cascadeVolumes[c][1], g, q), lobe)) * scale;
    const float b = std::max(0.0f, glm::dot(sampleSh(f.cascadeVolumes[c][2], g, q), lobe)) * scale;
    return 0.2126f * r + 0.7152f * gr + 0.0722f * b;
}

// The lookup's insideness (lpv_lookup.frag): 0 at a cascade's usable border, 1 a blend band in.
float insideness(const gi::VolumeGrid& g, glm::vec3 p) {
    const glm::vec3 uvw = (p - g.origin) / (g.cellSize * float(g.size));
    const float margin = 1.0f / float(g.size);
    const glm::vec3 d = glm::min(uvw - margin, (1.0f - margin) - uvw);
    return std::min({d.x, d.y, d.z}) / (0.25f * (0.5f - margin));
}

// Distance (in cells) from p to the cascade's border, negative outside.
float cellsInside(const gi::VolumeGrid& g, glm::vec3 p) {
    const glm::vec3 t = (p - g.origin) / g.cellSize;
    const glm::vec3 d = glm::min(t, glm::vec3(float(g.size)) - t);
    return std::min({d.x, d.y, d.z});
}

} // namespace

TEST_CASE("gi: moving the camera by less than a cell leaves the irradiance unchanged (cascades)") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame a = renderCornell(*device, kGi);
            REQUIRE(a.cascadeGrids.size() == 3);
            // A third of a finest cell sideways and a fifth of one forward.
            const float cell = a.cascadeGrids[0].cellSize;
            const CornellFrame b = renderCornell(*device, kGi, std::nullopt, 320, 240, 1,
                                                 glm::vec3(0.33f * cell, 0.0f, -0.2f * cell));
            for (size_t c = 0; c < a.cascadeGrids.size(); ++c) {
                // Points of a horizontal plane through the room, at least two cells inside the cascade in
                // both frames.
                std::vector<std::pair<float, float>> pairs;
                float peak = 0.0f;
                for (float x = -2.5f; x <= 2.5f; x += 0.25f)
                    for (float z = -2.5f; z <= 2.5f; z += 0.25f) {
                        const glm::vec3 p(x, 1.5f, z);
                        if (cellsInside(a.cascadeGrids[c], p) < 2.0f ||
                            cellsInside(b.cascadeGrids[c], p) < 2.0f)
                            continue;
                        pairs.push_back({irradiance(a, c, p, {0, 1, 0}), irradiance(b, c, p, {0, 1, 0})});
                        peak = std::max(peak, pairs.back().first);
                    }
                REQUIRE(!pairs.empty());
                REQUIRE(peak > 0.0f);
                float worst = 0.0f;
                for (const auto& [ea, eb] : pairs)
                    worst = std::max(worst, std::fabs(ea - eb) / peak);
                MESSAGE(backend.name << " cascade " << c << ": " << pairs.size()
                                     << " floor points, largest change " << 100.0f * worst
                                     << "% of the peak; origin moved by "
                                     << glm::length(b.cascadeGrids[c].origin - a.cascadeGrids[c].origin) /
                                            a.cascadeGrids[c].cellSize
                                     << " cells");
                CHECK(worst <= 0.01f);
            }
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: the irradiance is continuous across a cascade border") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // 0.1 m cells: the finest cascade (3.2 m) ends inside the room, between its centre and
            // the sunlit floor by the red wall; its light from there is handed in by cascade 1.
            std::vector<std::string> settings = kGi;
            settings.push_back("gi.cell_size=0.1");
            const CornellFrame f = renderCornell(*device, settings);
            REQUIRE(f.cascadeGrids.size() == 3);
            const gi::VolumeGrid& fine = f.cascadeGrids[0];
            const float border = fine.origin.x + fine.cellSize; // the usable region's -x edge
            REQUIRE(border > -2.0f);
            // From the room's middle in -x, across the border, toward the sunlit floor, in 1 cm
            // steps, half a metre above the floor: the lookup's blend of cascade 0 into cascade 1,
            // and each cascade alone.
            std::vector<float> blended, fineOnly, coarseOnly;
            float peak = 0.0f;
            for (float x = 0.0f; x >= border - 0.5f; x -= 0.01f) {
                const glm::vec3 p(x, 0.5f, 1.4f);
                const float w = insideness(fine, p);
                const float e0 = irradiance(f, 0, p, {0, 1, 0}), e1 = irradiance(f, 1, p, {0, 1, 0});
                blended.push_back(w >= 1.0f   ? e0
                                  : w <= 0.0f ? e1
                                              : glm::mix(e1, e0, glm::smoothstep(0.0f, 1.0f, w)));
                fineOnly.push_back(w > 0.0f ? e0 : blended.back());
                coarseOnly.push_back(e1);
                peak = std::max(peak, blended.back());
            }
            REQUIRE(peak > 0.0f);
            const auto largestStep = [](const std::vector<float>& v) {
                float worst = 0.0f;
                for (size_t i = 1; i < v.size(); ++i)
                    worst = std::max(worst, std::fabs(v[i] - v[i - 1]));
                return worst;
            };
            const float natural = largestStep(coarseOnly);
            const float blend = largestStep(blended), hard = largestStep(fineOnly);
            MESSAGE(backend.name << ": largest 1 cm step, in % of the line's peak: " << 100.0f * blend / peak
                                 << " blended, " << 100.0f * natural / peak << " in cascade 1 alone, "
                                 << 100.0f * hard / peak
                                 << " switching to cascade 1 at the border without a blend");
            // Stated tolerance: the blend adds at most 1% of the peak per cm to the steepest
            // change of the coarse cascade's own field.
            CHECK(blend <= natural + 0.01f * peak);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: coarse cascades updated in two halves on two frames match a whole update") {
    // Under gi.budget_policy=adapt with a budget nothing meets, the scheduler ends at its floor:
    // coarse cascades every 4 frames, each update split (light on one frame, volume on the next).
    // Static scene, camera and sun: the coarse results must equal one frame of the same load with
    // every cascade updated whole.
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const std::vector<std::string> base = {"gi.enabled=true", "gi.cascades=3", "render.ssao=false",
                                                   "gi.rsm_size=128", "gi.glossy=false"};
            platforms::PlatformProfile tight = platforms::loadPlatformProfile("pc");
            tight.giBudgetMs = 1e-3;
            engine::Scene scene = engine::buildCornellBox();
            const uint32_t w = 160, h = 120;
            std::vector<std::array<Image, 3>> split;
            gi::GiLoad reached;
            {
                engine::Config config;
                for (const std::string& s : base)
                    config.applyOverride(s, "test");
                config.applyOverride("gi.budget_policy=adapt", "test");
                engine::Renderer renderer(*device, w, h);
                renderer.setScene(scene);
                engine::FrameProfiler profiler(*device, tight);
                gi::LightPropagationVolume lpv(*device, tight);
                const engine::CameraMatrices camera =
                    engine::cameraMatrices(*scene.camera, float(w) / float(h));
                uint64_t stableSince = 0;
                uint32_t steps = ~0u;
                for (int f = 0; f < 200 && device->frameIndex() < stableSince + 12; ++f) {
                    REQUIRE(gi::updateFromConfig(lpv, config, renderer, camera, &profiler).accepted);
                    if (lpv.schedule().stepsInEffect != steps) {
                        steps = lpv.schedule().stepsInEffect;
                        stableSince = device->frameIndex();
                    }
                    rhi::CommandList& cmd = device->beginFrame();
                    profiler.beginFrame(cmd);
                    renderer.render(cmd, camera, config, &profiler, &lpv);
                    profiler.endFrame(cmd);
                    device->endFrame();
                }
                device->waitIdle();
                reached = lpv.schedule().load;
                MESSAGE(backend.name << ": coarse every " << reached.coarseUpdateInterval << " frames, "
                                     << reached.iterations << " iterations, rsm " << reached.rsmSize
                                     << ", steps " << steps << ", stable since frame " << stableSince);
                REQUIRE(reached.coarseUpdateInterval == 4);
                REQUIRE(gi::cascadeWorkOn(reached, 1, 0) == gi::kCascadeLight);
                for (uint32_t c = 1; c < 3; ++c) {
                    std::array<Image, 3> v;
                    for (uint32_t ch = 0; ch < 3; ++ch)
                        v[ch] = readImage(*device, lpv.cascadeResult(c)[ch]);
                    split.push_back(std::move(v));
                }
            }
            std::vector<std::string> whole = base;
            whole.push_back("gi.iterations=" + std::to_string(reached.iterations));
            whole.push_back("gi.rsm_size=" + std::to_string(reached.rsmSize));
            whole.push_back(reached.resolutionDivisor == 4 ? "gi.resolution=quarter" : "gi.resolution=half");
            const CornellFrame f = renderSceneFrame(*device, engine::buildCornellBox(), whole, {}, w, h);
            REQUIRE(f.cascadeVolumes.size() == 3);
            float peak = 0.0f;
            size_t differing = 0;
            for (uint32_t c = 1; c < 3; ++c)
                for (uint32_t ch = 0; ch < 3; ++ch) {
                    const Image& a = split[c - 1][ch];
                    const Image& b = f.cascadeVolumes[c][ch];
                    REQUIRE(a.texels.size() == b.texels.size());
                    for (size_t i = 0; i < a.texels.size(); ++i) {
                        peak = std::max(peak, std::fabs(b.texels[i].x));
                        if (a.texels[i] != b.texels[i]) ++differing;
                    }
                }
            MESSAGE(backend.name << ": " << differing << " differing texels in the coarse cascades, peak "
                                 << peak);
            CHECK(peak > 0.0f);
            CHECK(differing == 0);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: cascades propagated together match cascades one after another in a still scene") {
    // Together (gi.cascades_together), a finer cascade takes the coarser one's result of the frame
    // before at its border; the first frame propagates them one after another, as they have none.
    // In a still scene the result is the same from the second frame on, texel for texel. Where
    // branches are not masked, the volumes propagate stacked, one dispatch a step for all of them
    // (LpvPropagation::stacks); a CPU rasterizer, whose branches are, one dispatch per volume.
    for (const auto& backend : selectedBackends()) {
        for (const bool masked : {true, false})
            SUBCASE((backend.name + (masked ? ", a dispatch per volume" : ", stacked")).c_str()) {
                rhi::DeviceConfig config;
                config.maskedBranches = masked;
                TestDevice device(backend, config);
                gi::LpvSettings stackedSettings;
                stackedSettings.cascades = 3;
                REQUIRE(gi::LpvPropagation::stacks(device->caps(), stackedSettings, 4) == !masked);
                const auto frameWith = [&](const char* together, int frames) {
                    std::vector<std::string> settings = kGi;
                    settings.push_back("gi.cascades=3");
                    settings.push_back("gi.bounces=2");
                    settings.push_back(together);
                    return renderSceneFrame(*device, engine::buildCornellBox(), settings, {}, 160, 120,
                                            frames);
                };
                const CornellFrame serial = frameWith("gi.cascades_together=false", 3);
                const CornellFrame together = frameWith("gi.cascades_together=true", 3);
                // One frame together changes nothing either: it has no coarse result to take yet.
                const CornellFrame first = frameWith("gi.cascades_together=true", 1);
                const CornellFrame firstSerial = frameWith("gi.cascades_together=false", 1);
                REQUIRE(serial.cascadeVolumes.size() == 3);
                REQUIRE(together.cascadeVolumes.size() == 3);
                size_t differing = 0, differingFirst = 0;
                float peak = 0.0f;
                for (uint32_t c = 0; c < 3; ++c)
                    for (uint32_t ch = 0; ch < 3; ++ch) {
                        const Image& a = serial.cascadeVolumes[c][ch];
                        const Image& b = together.cascadeVolumes[c][ch];
                        REQUIRE(a.texels.size() == b.texels.size());
                        for (size_t i = 0; i < a.texels.size(); ++i) {
                            peak = std::max(peak, std::fabs(a.texels[i].x));
                            if (a.texels[i] != b.texels[i]) ++differing;
                            if (first.cascadeVolumes[c][ch].texels[i] !=
                                firstSerial.cascadeVolumes[c][ch].texels[i])
                                ++differingFirst;
                        }
                    }
                MESSAGE(backend.name << std::string(masked ? "" : ", stacked") << ": " << differing
                                     << " differing texels after 3 frames, " << differingFirst
                                     << " after 1; peak " << peak);
                CHECK(peak > 0.0f);
                CHECK(differing == 0);
                CHECK(differingFirst == 0);
                CHECK(serial.hdr.texels == together.hdr.texels);
                device.expectSilent();
            }
    }
}

namespace {

// Every cascade's result after each group of `frames` frames with its settings in turn, rendered
// by one LightPropagationVolume from the Cornell box's camera.
std::vector<std::array<Image, 3>>
cascadesAfter(rhi::Device& device, const std::vector<std::vector<std::string>>& settingsInTurn, int frames) {
    const engine::Scene scene = engine::buildCornellBox();
    engine::Renderer renderer(device, 160, 120);
    renderer.setScene(scene);
    gi::LightPropagationVolume lpv(device, platforms::loadPlatformProfile("pc"));
    const engine::CameraMatrices matrices = engine::cameraMatrices(*scene.camera, 160.0f / 120.0f);
    for (const std::vector<std::string>& settings : settingsInTurn) {
        engine::Config config;
        for (const std::string& s : settings)
            config.applyOverride(s, "test");
        for (int i = 0; i < frames; ++i) {
            REQUIRE(gi::updateFromConfig(lpv, config, renderer, matrices).accepted);
            rhi::CommandList& cmd = device.beginFrame();
            renderer.render(cmd, matrices, config, nullptr, &lpv);
            device.endFrame();
        }
    }
    device.waitIdle();
    std::vector<std::array<Image, 3>> out(lpv.cascadeCount());
    for (uint32_t c = 0; c < lpv.cascadeCount(); ++c)
        for (uint32_t ch = 0; ch < 3; ++ch)
            out[c][ch] = readImage(device, lpv.cascadeResult(c)[ch]);
    return out;
}

} // namespace

TEST_CASE("gi: stacked volumes follow the further bounces turned off and on") {
    // Stacked (a GPU's path), the further bounce's volume is a slab of the propagation's partial
    // sums: turning gi.bounces from 2 to 1 or from 1 to 2 remakes the propagation with one slab
    // fewer or more. The cascades then match a volume that always had the later settings.
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            rhi::DeviceConfig config;
            config.maskedBranches = false;
            TestDevice device(backend, config);
            std::vector<std::string> two = kGi, one = kGi;
            two.push_back("gi.cascades=3"), one.push_back("gi.cascades=3");
            two.push_back("gi.bounces=2"), one.push_back("gi.bounces=1");
            const auto toggled = cascadesAfter(*device, {two, one}, 3);
            const auto never = cascadesAfter(*device, {one}, 3);
            const auto back = cascadesAfter(*device, {one, two}, 3);
            const auto always = cascadesAfter(*device, {two}, 3);
            REQUIRE(toggled.size() == 3);
            size_t differing = 0, differingBack = 0;
            float peak = 0.0f;
            for (uint32_t c = 0; c < 3; ++c)
                for (uint32_t ch = 0; ch < 3; ++ch)
                    for (size_t i = 0; i < never[c][ch].texels.size(); ++i) {
                        peak = std::max(peak, std::fabs(never[c][ch].texels[i].x));
                        if (toggled[c][ch].texels[i] != never[c][ch].texels[i]) ++differing;
                        if (back[c][ch].texels[i] != always[c][ch].texels[i]) ++differingBack;
                    }
            MESSAGE(backend.name << ": " << differing << " texels differ after 2 -> 1 bounces, "
                                 << differingBack << " after 1 -> 2; peak " << peak);
            CHECK(peak > 0.0f);
            CHECK(differing == 0);
            CHECK(differingBack == 0);
            // Four cascades fill a dispatch: their bounce propagates after them.
            std::vector<std::string> four = two;
            four.push_back("gi.cascades=4");
            CHECK(cascadesAfter(*device, {four}, 2).size() == 4);
            device.expectSilent();
        }
    }
}

namespace {

// The finest cascade's result after frames from the scene's camera moved by each offset in turn.
std::array<Image, 3> finestAfterMoves(rhi::Device& device, const std::vector<std::string>& settings,
                                      const std::vector<glm::vec3>& offsets, gi::VolumeGrid& grid) {
    engine::Config config;
    for (const std::string& s : settings)
        config.applyOverride(s, "test");
    const engine::Scene scene = engine::buildCornellBox();
    engine::Renderer renderer(device, 160, 120);
    renderer.setScene(scene);
    gi::LightPropagationVolume lpv(device, platforms::loadPlatformProfile("pc"));
    for (const glm::vec3& offset : offsets) {
        engine::Camera camera = *scene.camera;
        camera.position += offset;
        const engine::CameraMatrices matrices = engine::cameraMatrices(camera, 160.0f / 120.0f);
        REQUIRE(gi::updateFromConfig(lpv, config, renderer, matrices).accepted);
        rhi::CommandList& cmd = device.beginFrame();
        renderer.render(cmd, matrices, config, nullptr, &lpv);
        device.endFrame();
    }
    device.waitIdle();
    grid = lpv.cascadeGrid(0);
    std::array<Image, 3> v;
    for (uint32_t ch = 0; ch < 3; ++ch)
        v[ch] = readImage(device, lpv.cascadeResult(0)[ch]);
    return v;
}

} // namespace

TEST_CASE("gi: together, the finest cascade's bounce taken from the frame before follows the camera") {
    // Together, one further bounce reflects the finest cascade's first bounce of the frame before,
    // placed where the cascade was then. The camera moves three finest cells between two frames:
    // the result is close to that of cascades one after another, which bounce this frame's light.
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            std::vector<std::string> settings = kGi;
            settings.push_back("gi.cascades=3");
            settings.push_back("gi.bounces=2");
            const float cell = 0.17f;
            const std::vector<glm::vec3> offsets = {glm::vec3(0.0f), glm::vec3(0.0f),
                                                    glm::vec3(3.0f * cell, 0.0f, 0.0f)};
            gi::VolumeGrid gridSerial, gridTogether;
            settings.push_back("gi.cascades_together=false");
            const auto serial = finestAfterMoves(*device, settings, offsets, gridSerial);
            settings.back() = "gi.cascades_together=true";
            const auto together = finestAfterMoves(*device, settings, offsets, gridTogether);
            REQUIRE(gridSerial.origin == gridTogether.origin);
            float peak = 0.0f, worst = 0.0f;
            double sumDiff = 0.0, sum = 0.0;
            for (uint32_t ch = 0; ch < 3; ++ch)
                for (size_t i = 0; i < serial[ch].texels.size(); ++i) {
                    const float a = serial[ch].texels[i].x, b = together[ch].texels[i].x;
                    peak = std::max(peak, std::fabs(a));
                    worst = std::max(worst, std::fabs(a - b));
                    sumDiff += std::fabs(a - b);
                    sum += std::fabs(a);
                }
            MESSAGE(backend.name << ": largest difference " << 100.0f * worst / peak << "% of the peak, mean "
                                 << 100.0 * sumDiff / sum << "% of the mean");
            CHECK(peak > 0.0f);
            // What differs is the light's and the camera's sampling of the moved volume; a bounce
            // left where it was computed, or moved the wrong way, differs by more (docs/tests.md).
            CHECK(worst <= 0.035f * peak);
            device.expectSilent();
        }
    }
}

// gi.cell_size = auto sizes the finest cascade to the room the camera stands in and places the
// cascades over it. A camera in the middle of a room, looking at a wall, on a ground 40 m across
// (the room measured in voxels of 0.625 m): the cascades used to be centred ahead of the camera,
// the wall behind it outside the finest cascade, and the room taken as its free span, short of
// its walls by up to a voxel on each side.
TEST_CASE("gi: gi.cell_size = auto places the cascades over the room the camera stands in") {
    engine::Scene scene = roomOnGround();
    scene.camera = engine::Camera{};
    scene.camera->position = {0.0f, 1.5f, 0.0f};
    scene.camera->forward = {1.0f, 0.0f, 0.0f};
    const glm::vec3 inner[2] = {{-3.0f, 0.0f, -2.0f}, {3.0f, 3.0f, 2.0f}};
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            engine::Config config;
            for (const char* setting : {"gi.enabled=true", "gi.cell_size=auto", "render.ssao=false"})
                config.applyOverride(setting, "test");
            engine::Renderer renderer(*device, 64, 48);
            renderer.setScene(scene);
            gi::LightPropagationVolume lpv(*device, platforms::loadPlatformProfile("pc"));
            lpv.setScene(scene);
            const engine::CameraMatrices matrices = engine::cameraMatrices(*scene.camera, 64.0f / 48.0f);
            REQUIRE(gi::updateFromConfig(lpv, config, renderer, matrices).accepted);
            rhi::CommandList& cmd = device->beginFrame();
            renderer.render(cmd, matrices, config, nullptr, &lpv);
            device->endFrame();
            device->waitIdle();
            for (uint32_t c = 0; c < 3; ++c) {
                const gi::VolumeGrid& grid = lpv.cascadeGrid(c);
                INFO("cascade " << c << ": cells of " << grid.cellSize << " m from " << grid.origin.x << ", "
                                << grid.origin.y << ", " << grid.origin.z);
                for (int a = 0; a < 3; ++a) {
                    CHECK(grid.origin[a] <= inner[0][a]);
                    CHECK(grid.origin[a] + grid.cellSize * float(grid.size) >= inner[1][a]);
                }
            }
            device.expectSilent();
        }
    }
}
