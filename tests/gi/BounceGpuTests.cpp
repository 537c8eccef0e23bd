// Multiple bounces (gi.bounces) on each backend, in the Cornell box without its boxes and with the
// sun straight down through the ceiling opening, so the direct light hits only the floor: the
// ceiling then receives more indirect light with 2 bounces than with 1 (the walls, lit by the
// floor's bounce, reflect onto it), each further bounce adds less than the one before, and the
// light a bounce adds over more iterations does not grow (energy stays bounded). And a change of
// the bounces or the RSM size while the game runs (adapt's knobs) keeps the cascades.
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/config/Config.h"
#include "engine/render/Renderer.h"
#include "engine/scene/BuiltinScenes.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <tuple>

using namespace lpv;
using namespace lpv::test;

namespace {

engine::Scene floorLitCornellBox() {
    engine::Scene scene = engine::buildCornellBox();
    std::erase_if(scene.instances, [&](const engine::Instance& i) {
        return scene.meshes[i.mesh].name.find("box") != std::string::npos;
    });
    return scene;
}

CornellFrame render(rhi::Device& device, uint32_t bounces, uint32_t iterations = 24) {
    // One volume of 32 cells of 0.25 m holds the whole box; light travels a cell per iteration,
    // so 24 iterations carry the floor's light to the ceiling 5.5 m up (a point inside the finest
    // cascade sees only that cascade's light, so more cascades would not help here).
    return renderSceneFrame(device, floorLitCornellBox(),
                            {"gi.enabled=true", "render.debug_view=indirect", "render.ssao=false",
                             "gi.cascades=1", "gi.glossy=false",
                             "gi.iterations=" + std::to_string(iterations),
                             "gi.bounces=" + std::to_string(bounces)},
                            [](engine::Renderer& r) { r.sun().direction = glm::vec3(0.0f, -1.0f, 0.0f); });
}

// Mean indirect luminance at points on the ceiling's underside, away from the opening.
float ceilingLight(const CornellFrame& f) {
    const glm::vec3 points[] = {{-1.6f, 5.49f, -1.5f},
                                {1.6f, 5.49f, -1.5f},
                                {-1.6f, 5.49f, 0.5f},
                                {1.6f, 5.49f, 0.5f},
                                {0.0f, 5.49f, -1.8f}};
    float sum = 0.0f;
    int seen = 0;
    for (const glm::vec3& p : points) {
        uint32_t x = 0, y = 0;
        if (!f.pixelOf(p, x, y)) continue;
        sum += luminance(f.hdr.at(x, y));
        ++seen;
    }
    REQUIRE(seen >= 3);
    return sum / float(seen);
}

// The volume's total L0 over all channels: its light, in the volume's units.
double volumeEnergy(const CornellFrame& f) {
    double sum = 0.0;
    for (const Image& channel : f.cascadeVolumes.at(0))
        for (const glm::vec4& t : channel.texels)
            sum += t.x;
    return sum;
}

} // namespace

TEST_CASE("gi: a second bounce lights the ceiling of a floor-lit Cornell box, and energy stays bounded") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame one = render(*device, 1);
            const CornellFrame two = render(*device, 2), three = render(*device, 3);
            const float c1 = ceilingLight(one), c2 = ceilingLight(two);
            const double e1 = volumeEnergy(one), e2 = volumeEnergy(two), e3 = volumeEnergy(three);
            MESSAGE(backend.name << ": ceiling indirect luminance, 1 bounce " << c1 << ", 2 bounces " << c2
                                 << "; volume energy 1/2/3 bounces " << e1 << " / " << e2 << " / " << e3);
            CHECK(c1 > 0.0f);
            // The second bounce must be visible on the ceiling, not a rounding difference.
            CHECK(c2 > 1.05f * c1);
            // Each bounce adds light, and less than the one before (albedo < 1, part escapes).
            CHECK(e2 > e1);
            CHECK(e3 > e2);
            CHECK(e3 - e2 < e2 - e1);

            // Over iterations: what 8 more iterations add shrinks (no growth, energy bounded).
            double previous = volumeEnergy(render(*device, 2, 8)), previousStep = 0.0;
            for (uint32_t iterations : {16u, 24u, 32u}) {
                const double e = iterations == 24 ? e2 : volumeEnergy(render(*device, 2, iterations));
                const double step = e - previous;
                MESSAGE(backend.name << ": 2 bounces, iterations " << iterations - 8 << " -> " << iterations
                                     << " add " << step);
                CHECK(step >= 0.0);
                if (previousStep > 0.0) CHECK(step < previousStep);
                previous = e, previousStep = step;
            }
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: further bounces are added in the gi.bounce_cascades finest cascades only") {
    // Three cascades; the coarse ones are left as one bounce made them unless gi.bounce_cascades
    // reaches them. (The finest also takes the coarse light beyond its border, so it is compared
    // only against bounces=1.)
    const auto frame = [](rhi::Device& device, uint32_t bounces, uint32_t bounceCascades) {
        return renderSceneFrame(
            device, floorLitCornellBox(),
            {"gi.enabled=true", "render.debug_view=indirect", "render.ssao=false", "gi.cascades=3",
             "gi.glossy=false", "gi.iterations=8", "gi.bounces=" + std::to_string(bounces),
             "gi.bounce_cascades=" + std::to_string(bounceCascades)},
            [](engine::Renderer& r) { r.sun().direction = glm::vec3(0.0f, -1.0f, 0.0f); });
    };
    const auto same = [](const std::array<Image, 3>& a, const std::array<Image, 3>& b) {
        for (size_t ch = 0; ch < 3; ++ch)
            if (a[ch].texels != b[ch].texels) return false;
        return true;
    };
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame one = frame(*device, 1, 1), finest = frame(*device, 2, 1),
                               all = frame(*device, 2, 3);
            REQUIRE(one.cascadeVolumes.size() == 3);
            CHECK_FALSE(same(finest.cascadeVolumes[0], one.cascadeVolumes[0]));
            for (size_t c = 1; c < 3; ++c) {
                CHECK(same(finest.cascadeVolumes[c], one.cascadeVolumes[c]));
                CHECK_FALSE(same(all.cascadeVolumes[c], one.cascadeVolumes[c]));
            }
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: GL and Vulkan compute the same light with 2 bounces") {
    CornellFrame gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = render(*device, 2);
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = render(*device, 2);
        device.expectSilent();
    }
    // Tolerance: 1% of the brightest indirect value per channel, on 99% of the pixels (as with 1).
    checkBackendsAgree(gl.hdr, vk.hdr, "2 bounces, indirect");
}

TEST_CASE("gi: a change of the RSM size or the bounces mid-run keeps the cascades and ends where a fresh "
          "run does") {
    // adapt's knobs change while coarse cascades keep earlier frames' results (gi/GiScheduler.h):
    // those results stay in use, and once each cascade has been made again, coarsest first, the frame
    // is the one a run with the new settings from the start gives. A spot light on the red wall
    // has an RSM of its own (gi.light_rsms), which the RSM size changes too.
    engine::Scene scene = engine::buildCornellBox();
    engine::Light spot;
    spot.name = "spot";
    spot.type = engine::LightType::Spot;
    spot.position = {0.5f, 3.0f, 2.0f};
    spot.direction = glm::normalize(glm::vec3(-2.75f, 1.0f, 1.5f) - spot.position);
    spot.innerConeAngle = 0.35f;
    spot.outerConeAngle = 0.5f;
    spot.intensity = 60.0f;
    scene.lights.push_back(spot);
    const auto settings = [](const char* rsm, const char* bounces) {
        engine::Config config;
        for (const char* s :
             {"gi.enabled=true", "render.debug_view=indirect", "render.ssao=false", "gi.cell_size=0.17",
              "gi.cascades=3", "gi.coarse_update_interval=2", "gi.occlusion=true", rsm, bounces})
            config.applyOverride(s, "test");
        return config;
    };
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            {
                // The spot adds its bounce to the indirect light through its RSM: without the spot,
                // or with it injected analytically (gi.light_rsms=0), the light differs.
                const engine::Config config = settings("gi.rsm_size=256", "gi.bounces=2");
                engine::Config analytic = config;
                analytic.applyOverride("gi.light_rsms=0", "test");
                const auto under = [](const engine::Config& c) {
                    return [&c](int) -> const engine::Config& { return c; };
                };
                engine::Scene withoutSpot = scene;
                withoutSpot.lights.pop_back();
                const double lit = meanLuminance(renderHdrAfterFrames(*device, scene, 1, under(config))),
                             unlit =
                                 meanLuminance(renderHdrAfterFrames(*device, withoutSpot, 1, under(config))),
                             injected =
                                 meanLuminance(renderHdrAfterFrames(*device, scene, 1, under(analytic)));
                MESSAGE(backend.name << ": mean indirect luminance " << lit << " with the spot's RSM, "
                                     << injected << " with the spot analytic, " << unlit << " without it");
                CHECK(lit > 1.1 * unlit);
                CHECK(std::fabs(lit - injected) > 0.05 * lit);
            }
            // From RSM 256 and 2 bounces to a smaller RSM, to 1 bounce, and from 1 bounce back to 2.
            for (const auto& [rsm, bounces, bouncesBefore] :
                 {std::tuple{"gi.rsm_size=128", "gi.bounces=2", "gi.bounces=2"},
                  {"gi.rsm_size=256", "gi.bounces=1", "gi.bounces=2"},
                  {"gi.rsm_size=256", "gi.bounces=2", "gi.bounces=1"}}) {
                const engine::Config before = settings("gi.rsm_size=256", bouncesBefore);
                const engine::Config after = settings(rsm, bounces);
                // `changeAt` frames at `before` (none: a fresh run), then the rest at `after`.
                const auto run = [&](int changeAt) {
                    return renderHdrAfterFrames(*device, scene, 9, [&](int i) -> const engine::Config& {
                        return i < changeAt ? before : after;
                    });
                };
                const Image fresh = run(0);
                float peak = 0.0f;
                for (const glm::vec4& t : fresh.texels)
                    peak = std::max({peak, t.r, t.g, t.b});
                REQUIRE(peak > 0.0f);
                // Changed on a frame of each phase of the coarse cascades' cycle, 5 or 4 frames before
                // the end: enough for cascade 2, then 1, then 0 to be made from the new light.
                for (const int changeAt : {4, 5}) {
                    const Image changed = run(changeAt);
                    float worst = 0.0f;
                    for (size_t i = 0; i < fresh.texels.size(); ++i)
                        for (int ch = 0; ch < 3; ++ch)
                            worst = std::max(worst, std::fabs(changed.texels[i][ch] - fresh.texels[i][ch]));
                    MESSAGE(backend.name << ": " << std::string(rsm) << ", " << std::string(bounces)
                                         << " (from " << std::string(bouncesBefore) << ") at frame "
                                         << changeAt << ": largest difference from a fresh run "
                                         << worst / peak << " of the peak");
                    CHECK(worst <= 1e-3f * peak);
                }
            }
            device.expectSilent();
        }
    }
}
