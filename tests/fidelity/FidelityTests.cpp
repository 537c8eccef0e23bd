// The GI's indirect light against the path tracer (issue 44's fidelity targets), on each backend:
// the standard Cornell box (bench/scenes/cornell-sun.gltf) lit by the sun through its open front,
// 128x128, the finest cascade sized to the room, default iterations; the reference is traced here
// (lpv_reference, 1 bounce, 512 samples a pixel: its own noise is about 5% relative RMSE).
//
// The propagation alone (gi.gather off, as the console profiles and the CPU rasterizers run it) is
// far from the targets (docs/gi-fidelity.md says why): its figures are guarded, no worse than
// measured. Tighten the guard as the GI gets closer.
//
// With gi.gather, the room lit through its door (bench/scenes/doorway.gltf) too, against the same
// targets: its ground seen through the door lies in the coarsest cascade.
//
// And the fog (issue 48) in the same box and view, its sun part alone (gi.enabled=false: the sun
// through its shadow map), against the reference's fogSun at 32 samples a pixel (the sun part is
// nearly noise-free): the mean per channel within 5% and the relative RMSE under 0.05 (measured
// 1.000 and 0.014 at fog.steps 24). The indirect part is far off (docs/gi-fidelity.md, "Fog").
#include "../support/TestDevice.h"

#include "EngineFog.h"
#include "EngineIndirect.h"
#include "FidelityMetrics.h"
#include "FidelityScenes.h"
#include "engine/scene/SceneLoading.h"
#include "reference/PathTracer.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <string>

using namespace lpv;
using namespace lpv::test;

namespace {

// The propagation alone, measured (vulkan and gl-egl alike) against the reference with glTF's
// specular layer over its surfaces (RayScene::Surfaces::Gltf): means 1.06/1.15/1.22, relative RMSE
// 1.502, 12.67% over 3x; guarded at 0.26 off 1, the RMSE plus 4% and the share plus half a point
// (as when the test was written). Against the Lambertian
// reference the test was written with, the same images gave 0.97/1.05/1.12 (the blue then within
// the 20% target), 1.344 and 11.98%: the engine did not change, its yardstick did.
constexpr float kGuardMeanOff = 0.26f;
constexpr float kGuardRelativeRmse = 1.56f;
constexpr float kGuardShareOver3x = 0.132f;
// With gi.gather, measured (vulkan and gl-egl alike) plus a point (6.2% and 4.2% with VPLs as
// points near a receiver).
constexpr float kGatherGuardSunOver3x = 0.019f;   // 0.9%
constexpr float kGatherGuardPointOver3x = 0.012f; // 0.2%

struct Traced {
    engine::Scene scene;
    reference::TracedImage image;
};

// One of the benchmark's scenes traced at 128x128, 512 samples a pixel (`bounces` diffuse bounces).
Traced traceScene(const char* file, uint32_t bounces = 1, uint32_t samples = 512) {
    Traced t{engine::loadScene(std::string(LPV_FIDELITY_SCENES) + "/" + file), {}};
    reference::TraceSettings s;
    s.width = s.height = 128;
    s.samplesPerPixel = samples;
    s.bounces = bounces;
    t.image = reference::trace(t.scene, *t.scene.camera, s);
    return t;
}

// Each traced once per process (ctest's gi.fidelity runs both backends in one, so each is traced
// once for them): the standard box lit through its front, and lit by a point light under its
// ceiling.
const Traced& cornellSun() {
    static const Traced traced = traceScene("cornell-sun.gltf");
    return traced;
}
const Traced& cornellPoint() {
    static const Traced traced = traceScene("cornell-point.gltf");
    return traced;
}
// The closed room lit through its door from the sunlit ground outside, 1024 samples a pixel: at
// 512 the engine's relative RMSE against it read 0.430, against 0.416 at 1024 (the reference's
// noise, about 0.15 of it in quadrature at 512).
const Traced& doorway() {
    static const Traced traced = traceScene("doorway.gltf", 1, 1024);
    return traced;
}

// With further bounces: the sun's box with two (as the benchmark's frames run them: the further
// bounce propagates with the cascades), the point light's with three (the bounces after the
// propagation).
const Traced& cornellSunTwoBounces() {
    static const Traced traced = traceScene("cornell-sun.gltf", 2, 1024);
    return traced;
}
const Traced& cornellPointThreeBounces() {
    static const Traced traced = traceScene("cornell-point.gltf", 3, 1024);
    return traced;
}

// The engine's figures for one of the benchmark's scenes with its settings and `extra`.
bench::FidelityFigures measure(const BackendUnderTest& backend, const Traced& ref,
                               const std::string& sceneName, const std::vector<std::string>& extra,
                               int frames = 3) {
    TestDevice device(backend);
    engine::Config config;
    config.applyOverride("gi.enabled=true", "test");
    for (const bench::FidelityScene& fs : bench::fidelityScenes(""))
        if (fs.name == sceneName)
            for (const std::string& s : fs.settings)
                config.applyOverride(s, "test");
    for (const std::string& s : extra)
        config.applyOverride(s, "test");
    const std::vector<glm::vec3> image =
        bench::renderEngineIndirect(*device, ref.scene, *ref.scene.camera, 128, 128, config, frames);
    device.expectSilent();
    const bench::FidelityFigures f =
        bench::compareIndirect(image, ref.image.indirect, {ref.image.normal, ref.image.hit});
    MESSAGE(backend.name << ", " << sceneName << ": mean ratio " << f.meanRatio.r << "/" << f.meanRatio.g
                         << "/" << f.meanRatio.b << ", relative RMSE " << f.relativeRmse << " ("
                         << f.relativeRmseScaled << " after x" << f.bestScale << "), ceilings "
                         << f.orientation.ceilings << ", floors " << f.orientation.floors << ", walls "
                         << f.orientation.walls << ", over 3x " << f.shareOver3x);
    return f;
}

// The fog comparison's medium in the same box, traced once per process.
const reference::TracedImage& cornellSunFog() {
    static const reference::TracedImage traced = [] {
        const bench::FidelityFog fog = bench::fidelityFog();
        reference::TraceSettings s;
        s.width = fog.width, s.height = fog.height;
        s.samplesPerPixel = 32;
        s.medium = fog.medium;
        return reference::trace(cornellSun().scene, *cornellSun().scene.camera, s);
    }();
    return traced;
}

} // namespace

TEST_CASE("gi: the Cornell box lit through its front, against the path tracer") {
    for (const BackendUnderTest& backend : selectedBackends()) {
        CAPTURE(backend.name);
        const bench::FidelityFigures f = measure(backend, cornellSun(), "cornell-sun", {});
        // The guard: no worse than measured (README, "How close to the truth").
        for (int c = 0; c < 3; ++c)
            CHECK(std::abs(f.meanRatio[c] - 1.0f) <= kGuardMeanOff);
        CHECK(f.relativeRmse <= kGuardRelativeRmse);
        CHECK(f.shareOver3x <= kGuardShareOver3x);
        CHECK(f.pixels > 128u * 128u / 2u);
    }
}

// gi.gather: the first bounce gathered from the VPLs. Issue 44's targets but the share over 3x:
// relative RMSE <= 0.45, every channel's mean within 20%, the ceilings' within 35%; the share over
// 3x guarded at its measure (README, "How close to the truth") plus a point.
TEST_CASE("gi: with gi.gather, the Cornell boxes lit by the sun and by a point light meet the targets") {
    const struct {
        const Traced& ref;
        const char* name;
        float shareOver3x;
    } scenes[] = {{cornellSun(), "cornell-sun", kGatherGuardSunOver3x},
                  {cornellPoint(), "cornell-point", kGatherGuardPointOver3x}};
    for (const BackendUnderTest& backend : selectedBackends()) {
        CAPTURE(backend.name);
        for (const auto& scene : scenes) {
            CAPTURE(scene.name);
            const bench::FidelityFigures f = measure(backend, scene.ref, scene.name, {"gi.gather=on"});
            for (int c = 0; c < 3; ++c)
                CHECK(std::abs(f.meanRatio[c] - 1.0f) <= 0.2f);
            CHECK(f.relativeRmse <= 0.45f);
            CHECK(std::abs(f.orientation.ceilings - 1.0f) <= 0.35f);
            CHECK(f.shareOver3x <= scene.shareOver3x);
            CHECK(f.pixels > 128u * 128u / 2u);
        }
    }
}

// gi.gather with further bounces: the second is reflected from the first gathered at the geometry
// volume's faces and gathered per pixel from them (GatheredReflection), the third reflected from
// the second's listed faces the same way. Against references of as many bounces (1024 samples a
// pixel: at 128 the reference's noise alone made the point light's relative RMSE 0.28 and put 2.0%
// of its pixels over 3x, against 0.17 and 1.7% at 1024). Both boxes, every target. The sun's with
// two: measured 0.98-1.01, relative RMSE 0.25, ceilings 1.05, 0.3% over 3x; 2.8% over 3x while a
// face reflected by the geometry volume's blocked share alone, which spreads a surface's rim to
// the faces beyond it (the box's front edges, black in the truth, took their light). The point
// light's with three: 0.92-0.93, 0.18, 0.87, 0.04%; its means were 0.78-0.80 (against the
// Lambertian reference) while the surfaces only its light sees (the tall block's top) had no
// albedo and reflected nothing (docs/gi-fidelity.md).
TEST_CASE("gi: with gi.gather, the further bounces of the Cornell boxes against the path tracer") {
    for (const BackendUnderTest& backend : selectedBackends()) {
        CAPTURE(backend.name);
        const bench::FidelityFigures sun =
            measure(backend, cornellSunTwoBounces(), "cornell-sun", {"gi.gather=on", "gi.bounces=2"});
        for (int c = 0; c < 3; ++c)
            CHECK(std::abs(sun.meanRatio[c] - 1.0f) <= 0.2f);
        CHECK(std::abs(sun.orientation.ceilings - 1.0f) <= 0.35f);
        CHECK(sun.relativeRmse <= 0.45f);
        CHECK(sun.shareOver3x <= 0.02f);
        CHECK(sun.pixels > 128u * 128u / 2u);

        // One frame: its figures are those of two to the last decimal (a still scene's cascades and
        // bounces are all made in its first; its 7 sets of VPLs and the third bounce's list make
        // the reflections the test's longest step on a CPU rasterizer).
        const bench::FidelityFigures point = measure(backend, cornellPointThreeBounces(), "cornell-point",
                                                     {"gi.gather=on", "gi.bounces=3"}, 1);
        for (int c = 0; c < 3; ++c)
            CHECK(std::abs(point.meanRatio[c] - 1.0f) <= 0.2f);
        CHECK(point.relativeRmse <= 0.45f);
        CHECK(std::abs(point.orientation.ceilings - 1.0f) <= 0.35f);
        CHECK(point.shareOver3x <= 0.02f);
        CHECK(point.pixels > 128u * 128u / 2u);
    }
}

// gi.gather in the room lit through its door, the finest cascade sized to the room (its walls in
// the blend band, where the next cascade answers most of the lookup): each surface's light comes
// from the finest cascade whose box holds it, and the sunlit ground beyond that box from the
// coarser cascades, marched through their faces, which hold the walls. Every target of issue 44,
// the means within 10%. Measured (vulkan and gl-egl alike): means 1.05, relative RMSE 0.416,
// ceilings 1.07, 1.3% over 3x. While the coarsest cascade
// was not gathered, the sunlit ground it answers for, seen through the door, lit itself (its
// propagated first bounce, injected and read half a cell above it): relative RMSE 0.828, guarded
// at 0.83; and while the finest cascade's VPLs beyond its box were marched through faces that end
// at the box, open beyond, the ground lit the room through its walls (docs/gi-fidelity.md).
TEST_CASE("gi: with gi.gather, the room lit through its door against the path tracer") {
    for (const BackendUnderTest& backend : selectedBackends()) {
        CAPTURE(backend.name);
        const bench::FidelityFigures f = measure(backend, doorway(), "doorway", {"gi.gather=on"});
        for (int c = 0; c < 3; ++c)
            CHECK(std::abs(f.meanRatio[c] - 1.0f) <= 0.1f);
        CHECK(f.relativeRmse <= 0.45f);
        CHECK(std::abs(f.orientation.ceilings - 1.0f) <= 0.35f);
        CHECK(f.shareOver3x <= 0.02f);
        CHECK(f.pixels > 128u * 128u / 2u);
    }
}

TEST_CASE("gi: the sun's light in the fog of the Cornell box, against the path tracer") {
    const Traced& scene = cornellSun();
    const reference::TracedImage& ref = cornellSunFog();
    const bench::FidelityFog fog = bench::fidelityFog();
    for (const BackendUnderTest& backend : selectedBackends()) {
        CAPTURE(backend.name);
        TestDevice device(backend);
        engine::Config config;
        config.applyOverride("gi.enabled=false", "test");
        const std::vector<glm::vec3> image = bench::renderEngineFog(
            *device, scene.scene, *scene.scene.camera, fog.width, fog.height, config, fog.medium);
        device.expectSilent();
        const bench::FidelityFigures f = bench::compareIndirect(image, ref.fogSun, {ref.normal, ref.hit});
        MESSAGE(backend.name << ": the fog's sun part, mean ratio " << f.meanRatio.r << "/" << f.meanRatio.g
                             << "/" << f.meanRatio.b << ", relative RMSE " << f.relativeRmse);
        for (int c = 0; c < 3; ++c)
            CHECK(std::abs(f.meanRatio[c] - 1.0f) <= 0.05f);
        CHECK(f.relativeRmse <= 0.05f);
        CHECK(f.pixels > fog.width * fog.height / 2u);
    }
}
