// No heap allocation in a steady-state frame: operator new is counted while frames of the full
// pipeline (renderer, profiler and its overlay, LPV) are recorded and submitted, after warm-up frames have
// filled the caches: the Cornell box, and the lights hall for the analytic lights and a spot light RSM (and
// its shadow map). Only allocations on the frame's own thread count: lavapipe JIT-compiles shader variants
// with LLVM on its queue thread, which is the driver's business. Runs without validation layers, whose own
// bookkeeping allocates on the calling thread.
#include "../support/TestDevice.h"

#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfilerOverlay.h"
#include "engine/render/Renderer.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/GiScheduler.h"
#include "gi/GiWork.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <initializer_list>
#include <new>

namespace {
thread_local bool gCounting = false;
std::atomic<uint64_t> gAllocations{0};
} // namespace

void* operator new(std::size_t size) {
    if (gCounting) gAllocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
    return operator new(size);
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}

using namespace lpv;

// Heap allocations on this thread while 4 frames of `scene` (GI on) are recorded and submitted,
// after 6 warm-up frames, with `extra` settings. `check` looks at the profiler and the LPV afterwards.
template <typename Check>
uint64_t steadyStateAllocations(const test::BackendUnderTest& backend, const engine::Scene& scene,
                                float cellSize, Check&& check, std::initializer_list<const char*> extra = {},
                                rhi::DeviceConfig config = {}) {
    config.backend = backend.kind;
    config.glHeadless = backend.glHeadless;
    config.allowFallback = false;
    auto device = rhi::createDevice(config);
    engine::Config settings;
    settings.applyOverride("gi.enabled=true");
    settings.applyOverride("gi.bounces=2"); // every GI pass, the further bounce included
    settings.set(*engine::SettingRegistry::global().find("gi.cell_size"), double(cellSize), "test");
    for (const char* e : extra)
        settings.applyOverride(e);
    engine::Renderer renderer(*device, 160, 120);
    renderer.setScene(scene);
    const auto profile = platforms::loadPlatformProfile("pc");
    engine::FrameProfiler profiler(*device, profile);
    gi::LightPropagationVolume lpv(*device, profile);
    // As a window's frames draw it (game/Game.cpp), onto a target large enough for its labels,
    // which it formats every frame (on the 160x120 frame its rows would be too short for text).
    engine::ProfilerOverlay overlay(*device);
    const rhi::TextureHandle window =
        device->createTexture({rhi::TextureKind::Tex2D, rhi::Format::RGBA8Srgb, 1280, 720, 1, 1,
                               rhi::kTextureColorTarget, "window", "test"});
    const engine::CameraMatrices camera = engine::cameraMatrices(*scene.camera, 160.0f / 120.0f);
    bool accepted = true; // checked after the counted frames: an assertion could allocate
    const auto frame = [&] {
        accepted = gi::updateFromConfig(lpv, settings, renderer, camera).accepted && accepted;
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, camera, settings, &profiler, &lpv);
        overlay.draw(cmd, profiler, window);
        profiler.endFrame(cmd);
        device->endFrame();
    };
    for (int i = 0; i < 6; ++i)
        frame(); // warm-up: caches, framebuffers, shader variants
    gAllocations = 0;
    gCounting = true;
    for (int i = 0; i < 4; ++i)
        frame();
    gCounting = false;
    CHECK(accepted);
    device->waitIdle();
    device->destroy(window);
    check(profiler, lpv);
    return gAllocations.load();
}

TEST_CASE("steady state: a frame with GI, the profiler and its overlay allocates nothing") {
    for (const auto& backend : test::selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            const uint64_t n = steadyStateAllocations(
                backend, engine::buildCornellBox(), 0.17f,
                [](const engine::FrameProfiler&, const gi::LightPropagationVolume&) {});
            MESSAGE(backend.name << ": " << n << " allocations in 4 steady-state frames");
            CHECK(n == 0);
        }
        // As a GPU runs it: the lookup per texel, the propagation's volumes stacked.
        SUBCASE((backend.name + ", a GPU's branches").c_str()) {
            rhi::DeviceConfig gpu;
            gpu.maskedBranches = false;
            const uint64_t n = steadyStateAllocations(
                backend, engine::buildCornellBox(), 0.17f,
                [](const engine::FrameProfiler&, const gi::LightPropagationVolume&) {}, {}, gpu);
            MESSAGE(backend.name << ", a GPU's branches: " << n << " allocations in 4 steady-state frames");
            CHECK(n == 0);
        }
    }
}

TEST_CASE("steady state: rgba8 volumes that clip, read back and reported, allocate nothing") {
    for (const auto& backend : test::selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            // Range 4 clips the Cornell box (2.4x): every frame binds and reads back the clipping
            // records, and the report (during the warm-up) keeps its peak.
            const uint64_t n = steadyStateAllocations(
                backend, engine::buildCornellBox(), 0.17f,
                [](const engine::FrameProfiler&, const gi::LightPropagationVolume& lpv) {
                    REQUIRE(lpv.volumes());
                    REQUIRE(lpv.volumes()->clipping());
                    const auto& peaks = lpv.volumes()->clipping()->peaks();
                    CHECK(*std::max_element(peaks.begin(), peaks.end()) > gi::kReportedClipping);
                },
                {"gi.sh_format=rgba8", "gi.rgba8_range=4"});
            MESSAGE(backend.name << ": " << n << " allocations in 4 steady-state frames");
            CHECK(n == 0);
        }
    }
}

TEST_CASE(
    "steady state: the lights hall with analytic lights and spot and point light RSMs allocates nothing") {
    const engine::Scene hall = engine::buildLightHall();
    for (const auto& backend : test::selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            const auto check = [&](const engine::FrameProfiler& p, const gi::LightPropagationVolume& lpv) {
                // The pass ran as gi/lights with the work of 146 lights in every cascade (the hall
                // fits the finest volume; the last call is the coarsest's): all but the spot light
                // with an RSM of its own (gi.light_rsms=1), which ran as gi/lightrsm.
                const auto& scopes = p.scopes();
                const auto it = std::find_if(scopes.begin(), scopes.end(), [](const engine::ScopeInfo& s) {
                    return s.path == "gi/lights";
                });
                REQUIRE(it != scopes.end());
                REQUIRE(lpv.pointLights());
                CHECK(lpv.pointLights()->lights().size() == 146);
                const engine::WorkCounts last =
                    gi::analyticLightsWork(lpv.settings(), 146, lpv.pointLights()->cellEvaluations());
                CHECK(it->work.aluOps > last.aluOps);
                CHECK(it->work.cells == lpv.cascadeCount() * 32u * 32u * 32u);
                const auto rsm = std::find_if(scopes.begin(), scopes.end(), [](const engine::ScopeInfo& s) {
                    return s.path == "gi/lightrsm";
                });
                REQUIRE(rsm != scopes.end());
                // Its work counts the triangles drawn in the spot light's view: the hall's few large
                // boxes all reach it.
                CHECK(rsm->work == gi::lightRsmWork(lpv.settings(), 1, hall.triangleCount()));
                // That spot, lit per pixel, also got a shadow map (render.spot_shadows), drawn in
                // these frames too.
                const auto shadow =
                    std::find_if(scopes.begin(), scopes.end(),
                                 [](const engine::ScopeInfo& s) { return s.path == "render.light_shadows"; });
                REQUIRE(shadow != scopes.end());
                CHECK(shadow->work.primitives > 0);
            };
            // Every point light analytic here; the default's cube RSM for the brightest is below.
            const uint64_t n = steadyStateAllocations(backend, hall, 0.25f, check, {"gi.point_light_rsms=0"});
            MESSAGE(backend.name << ": " << n << " allocations in 4 steady-state frames");
            CHECK(n == 0);
            // At the defaults the brightest point light also gets a cube RSM (gi.point_light_rsms=1),
            // drawn with the spot's as gi/lightrsm: six more RSMs, still nothing allocated.
            const auto cube = [&](const engine::FrameProfiler& p, const gi::LightPropagationVolume& lpv) {
                REQUIRE(lpv.pointLights());
                CHECK(lpv.pointLights()->lights().size() == 145);
                const auto& scopes = p.scopes();
                CHECK(std::any_of(scopes.begin(), scopes.end(),
                                  [](const engine::ScopeInfo& s) { return s.path == "gi/lightrsm"; }));
            };
            const uint64_t withCube = steadyStateAllocations(backend, hall, 0.25f, cube);
            MESSAGE(backend.name << ": " << withCube
                                 << " allocations in 4 steady-state frames with a cube RSM");
            CHECK(withCube == 0);
        }
    }
}

TEST_CASE("steady state: the GI budget scheduler and the profiler's notes allocate nothing") {
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    auto device = rhi::createDevice(config);
    const auto profile = platforms::loadPlatformProfile("x360");
    engine::FrameProfiler profiler(*device, profile);
    gi::GiBudgetScheduler scheduler;
    gi::GiLoad configured;
    configured.cascades = 3;
    gi::GiLoad load = configured;
    uint64_t changes = 0;
    // GI's time follows the load; the budget is tight, then loose, so steps are taken and given
    // back (and noted) while allocations are counted.
    const auto frame = [&](double budgetMs) {
        const uint64_t index = device->frameIndex() + 1;
        std::optional<gi::GiFrameCost> cost = gi::giFrameCost(profiler);
        if (cost) cost->ms = 0.4 * load.iterations; // about the load of that frame
        const gi::GiSchedule& s = scheduler.schedule(index, cost, {budgetMs, profile.giMemoryBudgetBytes},
                                                     configured, gi::GiBudgetPolicy::Adapt);
        for (const gi::GiChange& c : s.changes())
            profiler.note(gi::kGiBudgetNoteTopic, c.text());
        changes += s.changes().size();
        load = s.load;
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        {
            auto gi = profiler.scope("gi", &cmd);
            cmd.dispatch(1);
        }
        profiler.endFrame(cmd);
        device->endFrame();
    };
    for (int i = 0; i < 4; ++i)
        frame(2.0);
    gAllocations = 0;
    gCounting = true;
    for (int i = 0; i < 80; ++i)
        frame(2.0);
    for (int i = 0; i < 300; ++i)
        frame(10.0);
    gCounting = false;
    MESSAGE(changes << " schedule changes noted, " << gAllocations.load() << " allocations");
    CHECK(changes >= 4);
    CHECK(gAllocations.load() == 0);
}
