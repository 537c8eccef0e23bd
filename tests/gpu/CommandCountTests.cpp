// Commands a frame records, pinned (issue 46): the frames benchmark's settings (3 x 32^3 cascades, 8
// iterations, occlusion, 2 bounces, glossy) in the atrium at 320x180 from its own camera, on Vulkan
// and GL: dispatches, draws and vkCmdPipelineBarrier2 (glMemoryBarrier) calls per steady frame,
// per pass and in the GI's dependent-pass chain. A pass that grows by a dispatch or a barrier fails
// here; one that shrinks updates the numbers on purpose.
#include "../support/TestDevice.h"

#include "engine/config/Config.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/render/Renderer.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/LightPropagationVolume.h"
#include "gi/adapter/EngineFrame.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <map>
#include <optional>
#include <string>
#include <utility>

using namespace lpv;

namespace {

struct Counted {
    rhi::CommandCounts frame;                         // Device::frameCounters(): the whole frame
    std::map<std::string, rhi::CommandCounts> passes; // by scope path, of the last frame
};

std::string describe(const rhi::CommandCounts& c) {
    return std::to_string(c.dispatches) + " dispatches, " + std::to_string(c.draws) + " draws, " +
           std::to_string(c.drawsIndexed) + " indexed draws, " + std::to_string(c.barriers) + " barriers, " +
           std::to_string(c.stages) + " stages";
}

// Steady frames of the benchmark's settings; checks that two of them recorded the same commands.
// `gather`: with the per-pixel gather, as a GPU runs them (gi.gather = auto leaves it off on the
// CPU rasterizers here).
Counted countAtrium(const test::BackendUnderTest& backend, rhi::DeviceConfig base = {}, bool gather = false) {
    test::TestDevice device(backend, base);
    engine::Config settings;
    for (const char* s :
         {"gi.enabled=true", "gi.grid_size=32", "gi.iterations=8", "gi.bounces=2", "gi.cell_size=1.0"})
        settings.applyOverride(s, "test");
    if (gather) settings.applyOverride("gi.gather=on", "test");
    const engine::Scene scene = engine::buildBuiltinScene("atrium");
    engine::Renderer renderer(*device, 320, 180);
    renderer.setScene(scene);
    const auto profile = platforms::loadPlatformProfile("pc");
    engine::FrameProfiler profiler(*device, profile);
    gi::LightPropagationVolume lpv(*device, profile);
    const engine::CameraMatrices camera = engine::cameraMatrices(*scene.camera, 320.0f / 180.0f);
    rhi::CommandCounts previous;
    for (int i = 0; i < 5; ++i) {
        static_cast<void>(gi::updateFromConfig(lpv, settings, renderer, camera));
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, camera, settings, &profiler, &lpv);
        profiler.endFrame(cmd);
        device->endFrame();
        if (i == 4) CHECK_MESSAGE(device->frameCounters() == previous, describe(previous));
        previous = device->frameCounters();
    }
    device->waitIdle();
    device.expectSilent();
    Counted out{device->frameCounters(), {}};
    for (const engine::ScopeInfo& s : profiler.scopes())
        out.passes[s.path] = s.commands;
    return out;
}

// What one backend must record: the frame's and the GI's counts, and one pass's, with barriers at
// hazards and with the conservative rule.
struct Pinned {
    rhi::CommandCounts frame, gi;
    const char* pass;
    rhi::CommandCounts passCounts;
    // gi/propagate: the 3 cascades' and the further bounce's seeds and 8 iterations, together.
    rhi::CommandCounts propagate;
    rhi::CommandCounts conservativeFrame, conservativeGi;
    // As a GPU runs it (DeviceConfig::maskedBranches false, gi.gather on): the propagation's
    // volumes stacked, one dispatch a step for all of them (LpvPropagation::stacks).
    rhi::CommandCounts stackedFrame, stackedGi, stackedPropagate;
    // Vulkan with its textures in the layout of each use (DeviceConfig::unifiedImageLayouts
    // false, as on a GPU without unified layouts; gi.gather on): render passes move their targets.
    std::optional<std::pair<rhi::CommandCounts, rhi::CommandCounts>> layoutsPerUse;
};

// {dispatches, draws, indexed draws, barriers, stages}.
Pinned pinnedFor(rhi::BackendKind kind) {
    if (kind == rhi::BackendKind::Vulkan)
        // A dispatch's barrier is owed to the next command that needs it (CommandList.h), merged
        // into a render pass's or a clear's own; the chain of dependent dispatches still needs one
        // each. A clear of a storage image owes its barrier too (92 -> 82: the injection's three
        // clears of each cascade share the render pass's barrier, and an occlusion clear its
        // dispatch's). A render pass owes its own (its targets back home) to the next command,
        // which pays it in its own (82 -> 76). The cascades propagate together, one stage per step
        // for all three (76 -> 58; GI chain 62 -> 44), and the finest cascade's further bounce with
        // them, from its first bounce of the frame before (58 -> 49; GI chain 44 -> 35), and the
        // cascades' geometry volumes are built together (49 -> 45; GI chain 35 -> 31). With
        // unified layouts (lavapipe, a CPU device, has them) nothing moves: a render pass begins
        // at its first draw, behind a barrier only where its targets or what its draws bind meet
        // a hazard, and the frame's end makes the host's reads visible in the same call (45 -> 29;
        // GI chain 31 -> 23). Each cascade draws an RSM of its own, so every RSM, then every VPL
        // clustering, then every injection run as one stage each, and the injection and the
        // geometry volume's coverage are cleared by their passes (29 -> 25; GI chain 23 -> 19). A
        // frame begins with no barrier: the one before ended with a full one (25 -> 24).
        // The RSMs and the G-buffer draw the scene by texture set, an indirect multi-draw each,
        // the sun's shadow in one (engine::MultiDraw: indexed draw calls 852 -> 38, the GI's
        // 418 -> 27).
        // The conservative rule: a barrier after every command (the issue counted 100
        // vkCmdPipelineBarrier2 calls, with the moves of layouts per use and separate clears). The
        // GI's stages are its dependent-pass chain. As a GPU runs it, with gi.gather: the gather's
        // draws (the sun's VPLs of the two finest cascades) and the copy of cascade 1's first
        // bounce, its three textures behind one barrier (CommandList::copyTextures), beside the
        // chain: 24 -> 25 barriers, chain unchanged; the further bounce reflected from the
        // gathered first (GatheredReflection: its list's counter cleared by the frame before, the
        // finest cascade's first two bounces kept by the bounce's sum) and gathered in one more
        // draw: no barrier more. The gather's visibility, the scene drawn onto the faces of the
        // two finest cascades (SurfaceVoxels): one multi-draw each for the three axes, with its
        // cascade's own faces and target, beside the chain: 2 indexed draws, no barrier more.
        // With layouts per use (a GPU without unified layouts) each render pass moves its
        // targets: 40 barriers, GI chain 32. The third cascade gathered too (VplGather::kCascades):
        // one more draw for its sun's VPLs and one more multi-draw of its faces, no barrier more
        // (41 with layouts per use, the third faces' target moved; GI chain 33). The sun's VPLs
        // listed by window before the gather's draws (VplWindows): a dispatch per gathered
        // cascade, beside each other, and one barrier before the draws read the lists: 25 -> 26
        // barriers, GI chain 19 -> 20 (42 and 34 with layouts per use).
        return {{50, 109, 38, 24, 24},
                {50, 105, 27, 19, 19},
                "gi/cascade0/inject",
                {0, 16, 0, 0, 0},
                {36, 0, 0, 9, 9},
                {50, 109, 38, 72, 68},
                {50, 105, 27, 65, 62},
                {26, 106, 41, 26, 25},
                {26, 102, 30, 21, 20},
                {9, 0, 0, 9, 9},
                std::pair{rhi::CommandCounts{53, 113, 41, 42, 40}, rhi::CommandCounts{53, 109, 30, 35, 34}}};
    // GL: a command pays one glMemoryBarrier, with the bits it needs, only where it touches what
    // earlier shaders stored to (or stores to what they read) since a barrier covered it
    // (GlHazards.h); GL orders framebuffer writes, clears and copies with later commands itself.
    // The cascades and the further bounce propagate together, the cascades' geometry volumes are
    // built together, and their light halves run phase by phase (48 -> 29 -> 21 -> 19 -> 17; GI
    // chain 47 -> 28 -> 20 -> 18 -> 16). The conservative rule: glMemoryBarrier(GL_ALL_BARRIER_BITS)
    // after every dispatch, render pass and transfer (84, 72 since the injection's and the
    // coverage's clears are their passes'). The multi-draws as on Vulkan; gi.gather's copy needs
    // no glMemoryBarrier of its own, nor do its surfaces' faces (3 indexed draws, one a gathered
    // cascade) or its draws (one per set of VPLs). The lists of the sun's VPLs by window
    // (VplWindows): 3 dispatches and one glMemoryBarrier before the draws read them.
    return {{50, 19, 38, 17, 17}, {50, 15, 27, 16, 16}, "render.gbuffer",     {0, 0, 10, 0, 0},
            {36, 0, 0, 9, 9},     {50, 19, 38, 72, 68}, {50, 15, 27, 65, 62}, {26, 16, 41, 18, 18},
            {26, 12, 30, 17, 17}, {9, 0, 0, 9, 9},      std::nullopt};
}

} // namespace

TEST_CASE("render: the benchmark's atrium frame records its pinned commands") {
    for (const auto& backend : test::selectedBackends()) {
        const Pinned pinned = pinnedFor(backend.kind);
        SUBCASE(backend.name.c_str()) {
            const Counted c = countAtrium(backend);
            MESSAGE("frame: " << describe(c.frame));
            for (const auto& [path, n] : c.passes)
                MESSAGE(path << ": " << describe(n));
            CHECK(c.frame == pinned.frame);
            CHECK(c.passes.at("gi") == pinned.gi);
            CHECK(c.passes.at(pinned.pass) == pinned.passCounts);
            CHECK(c.passes.at("gi/propagate") == pinned.propagate);
        }
        SUBCASE((backend.name + ", conservative barriers").c_str()) {
            rhi::DeviceConfig conservative;
            conservative.conservativeBarriers = true;
            const Counted c = countAtrium(backend, conservative);
            MESSAGE("conservative frame: " << describe(c.frame) << "; gi: " << describe(c.passes.at("gi")));
            CHECK(c.frame == pinned.conservativeFrame);
            CHECK(c.passes.at("gi") == pinned.conservativeGi);
        }
        SUBCASE((backend.name + ", a GPU's branches").c_str()) {
            rhi::DeviceConfig gpu;
            gpu.maskedBranches = false;
            const Counted c = countAtrium(backend, gpu, true);
            MESSAGE("unmasked frame: " << describe(c.frame) << "; gi: " << describe(c.passes.at("gi"))
                                       << "; gi/propagate: " << describe(c.passes.at("gi/propagate")));
            CHECK(c.frame == pinned.stackedFrame);
            CHECK(c.passes.at("gi") == pinned.stackedGi);
            CHECK(c.passes.at("gi/propagate") == pinned.stackedPropagate);
        }
        if (pinned.layoutsPerUse) {
            SUBCASE((backend.name + ", layouts per use").c_str()) {
                rhi::DeviceConfig perUse;
                perUse.unifiedImageLayouts = false;
                const Counted c = countAtrium(backend, perUse, true);
                MESSAGE("layouts per use frame: " << describe(c.frame)
                                                  << "; gi: " << describe(c.passes.at("gi")));
                CHECK(c.frame == pinned.layoutsPerUse->first);
                CHECK(c.passes.at("gi") == pinned.layoutsPerUse->second);
            }
        }
    }
}
