// The in-window profiler overlay on each backend: its rows fit the window they are drawn in.
#include "../support/Image.h"
#include "../support/TestDevice.h"

#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfilerOverlay.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <string>

using namespace lpv;
using namespace lpv::test;

namespace {

// The rows of `image` holding any overlay pixel, the first and the last (-1: none).
std::pair<int, int> overlayRows(const Image& image) {
    int first = -1, last = -1;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x)
            if (image.at(x, y).x + image.at(x, y).y + image.at(x, y).z > 0.0f) {
                if (first < 0) first = int(y);
                last = int(y);
                break;
            }
    return {first, last};
}

} // namespace

// At 13 pixels a row, the 40-odd passes of a GI frame ran off the bottom of a 640x360 window.
TEST_CASE("render: the profiler overlay's rows fit the window's height") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            engine::FrameProfiler profiler(*device, platforms::loadPlatformProfile("pc"));
            for (int f = 0; f < 3; ++f) { // GPU times arrive frames later
                rhi::CommandList& cmd = device->beginFrame();
                profiler.beginFrame(cmd);
                {
                    auto gi = profiler.scope("gi", &cmd);
                    for (int i = 0; i < 40; ++i)
                        auto pass = profiler.scope("pass" + std::to_string(i), &cmd);
                }
                profiler.endFrame(cmd);
                device->endFrame();
            }
            engine::ProfilerOverlay overlay(*device);
            for (const uint32_t height : {360u, 156u, 120u, 40u}) {
                CAPTURE(height);
                const rhi::TextureHandle target = device->createTexture(
                    {rhi::TextureKind::Tex2D, rhi::Format::RGBA8Srgb, 320, height, 1, 1,
                     rhi::kTextureColorTarget | rhi::kTextureTransfer, "overlay", "test"});
                rhi::CommandList& cmd = device->beginFrame();
                rhi::RenderPassDesc clear;
                clear.colors[0] = {target, 0, 0, rhi::LoadOp::Clear, {0, 0, 0, 1}};
                clear.colorCount = 1;
                cmd.beginRenderPass(clear);
                cmd.endRenderPass();
                overlay.draw(cmd, profiler, target);
                device->endFrame();
                device->waitIdle();
                const Image image = readImage(*device, target);
                const auto [first, last] = overlayRows(image);
                MESSAGE(backend.name << " " << height << " rows high: overlay from row " << first << " to "
                                     << last);
                CHECK(first == 8);                  // the backdrop, 4 pixels above the first bar
                CHECK(last <= int(height) - 8);     // and as far from the bottom
                CHECK(last >= int(height) * 2 / 3); // the rows use the height they have
                device->destroy(target);
            }
            device.expectSilent();
        }
    }
}
