// The console preset (gi/presets/console.toml: 3 x 24^3 cascades of RGBA8, the coarse ones every
// other frame, occlusion, 2 bounces, glossy, quarter-resolution lookup) on GL and Vulkan: the same
// image, with indirect light in it. Three frames: without a profiler the LPV still spaces the
// coarse cascades as configured, so the second and third frames draw with one coarse cascade kept
// from an earlier frame (the cadence itself is checked on the null device, ConsolePresetTests).
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/scene/BuiltinScenes.h"

#include <doctest/doctest.h>

using namespace lpv;
using namespace lpv::test;

TEST_CASE("gi: the console preset renders the Cornell box the same on GL and Vulkan") {
    // 24 cells of 0.23 m span the 5.5 m box.
    const std::vector<std::string> preset = {LPV_CONSOLE_PRESET, "gi.cell_size=0.23"};
    const FramesOnBothApis f = renderOnGlAndVulkan(engine::buildCornellBox(), preset, {}, 3);
    REQUIRE(f.vk.indirectDivisor == 4);
    REQUIRE(f.gl.indirectDivisor == 4);
    // The indirect target holds light on both (the room is lit through its roof opening).
    MESSAGE("mean indirect luminance: GL " << meanLuminance(f.gl.indirect) << ", Vulkan "
                                           << meanLuminance(f.vk.indirect));
    CHECK(meanLuminance(f.gl.indirect) > 0.01);
    CHECK(meanLuminance(f.vk.indirect) > 0.01);
    // As the renderer's GL/Vulkan test: 3 8-bit steps per channel; at most 1% of the pixels
    // (triangle and shadow edges, where the rasterizers may cover different samples) beyond it.
    const ImageDifference d = compareImages(f.gl.output, f.vk.output, 3.0f / 255.0f + 1e-4f);
    MESSAGE("GL vs Vulkan: max difference " << d.maxAbs << ", " << d.texelsOver << " of "
                                            << f.gl.output.texels.size() << " pixels over tolerance");
    CHECK(d.texelsOver <= f.gl.output.texels.size() / 100);
}
