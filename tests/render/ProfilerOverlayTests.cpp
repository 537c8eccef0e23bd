// The in-window profiler overlay on each backend: its rows fit the window they are drawn in, and its
// labels are drawn where its layout puts them, the same pixels on GL and Vulkan.
#include "../support/Image.h"
#include "../support/TestDevice.h"

#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfilerOverlay.h"
#include "platforms/PlatformProfile.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

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

// A profile on the null device, whose simulated clock (1 us a command) gives the same medians on
// every run: two passes of 1.5 and 0.75 ms inside "gi", four frames.
void nullProfile(rhi::Device& null, engine::FrameProfiler& profiler) {
    for (int f = 0; f < 4; ++f) {
        rhi::CommandList& cmd = null.beginFrame();
        profiler.beginFrame(cmd);
        {
            auto gi = profiler.scope("gi", &cmd);
            for (const auto& [name, dispatches] : {std::pair{"propagate", 1500}, std::pair{"lookup", 750}}) {
                auto pass = profiler.scope(name, &cmd);
                for (int i = 0; i < dispatches; ++i)
                    cmd.dispatch(1);
            }
        }
        profiler.endFrame(cmd);
        null.endFrame();
    }
    profiler.collectPending();
}

// `overlay` drawn on a black width x height target of `device`, read back.
Image drawOverlay(rhi::Device& device, engine::ProfilerOverlay& overlay,
                  const engine::FrameProfiler& profiler, uint32_t width, uint32_t height) {
    const rhi::TextureHandle target =
        device.createTexture({rhi::TextureKind::Tex2D, rhi::Format::RGBA8Srgb, width, height, 1, 1,
                              rhi::kTextureColorTarget | rhi::kTextureTransfer, "overlay", "test"});
    rhi::CommandList& cmd = device.beginFrame();
    rhi::RenderPassDesc clear;
    clear.colors[0] = {target, 0, 0, rhi::LoadOp::Clear, {0, 0, 0, 1}};
    clear.colorCount = 1;
    cmd.beginRenderPass(clear);
    cmd.endRenderPass();
    overlay.draw(cmd, profiler, target);
    device.endFrame();
    device.waitIdle();
    Image image = readImage(device, target);
    device.destroy(target);
    return image;
}

// The overlay of `profiler` drawn at 640x360 on `backend`.
Image drawOverlay(const BackendUnderTest& backend, const engine::FrameProfiler& profiler) {
    TestDevice device(backend);
    engine::ProfilerOverlay overlay(*device);
    Image image = drawOverlay(*device, overlay, profiler, 640, 360);
    device.expectSilent();
    return image;
}

} // namespace

// The labels are axis-aligned rectangles on whole pixels, so both APIs fill the same pixels.
TEST_CASE("render: the profiler overlay's labels are the same pixels on GL and Vulkan") {
    auto null = nullDevice();
    engine::FrameProfiler profiler(*null, platforms::loadPlatformProfile("pc"));
    nullProfile(*null, profiler);
    const Image gl = drawOverlay(backendByName("gl-egl"), profiler);
    const Image vk = drawOverlay(backendByName("vulkan"), profiler);
    const ImageDifference d = compareImages(gl, vk, 1.0f / 255.0f + 1e-4f);
    MESSAGE("largest difference " << d.maxAbs << ", " << d.texelsOver << " pixels over one 8-bit step");
    CHECK(d.texelsOver == 0);

    // Left of the bars (the frame's bar, the layout's second rectangle, starts them) only the
    // labels are bright: every pixel a glyph rectangle covers, and no other. The glyphs follow the
    // backdrop, the frame's bar, a bar per pass and the budget line.
    std::vector<engine::OverlayRect> rects(engine::ProfilerOverlay::kMaxRects);
    rects.resize(engine::ProfilerOverlay::layout(profiler, 640, 360, rects));
    const size_t firstGlyph = profiler.scopes().size() + 3;
    REQUIRE(rects.size() > firstGlyph);
    const uint32_t barsX = uint32_t(rects[1].rect.x);
    std::vector<uint8_t> glyph(640 * 360, 0);
    for (size_t i = firstGlyph; i < rects.size(); ++i) {
        const engine::OverlayRect& r = rects[i];
        if (r.rect.x >= float(barsX)) continue; // the medians' column
        for (uint32_t y = uint32_t(r.rect.y); y < uint32_t(r.rect.y + r.rect.w); ++y)
            for (uint32_t x = uint32_t(r.rect.x); x < uint32_t(r.rect.x + r.rect.z); ++x)
                glyph[y * 640 + x] = 1;
    }
    uint32_t covered = 0, wrong = 0;
    for (uint32_t y = 0; y < 360; ++y)
        for (uint32_t x = 0; x < barsX; ++x) {
            covered += glyph[y * 640 + x];
            for (const Image* image : {&gl, &vk})
                wrong += (image->at(x, y).x > 0.5f) != bool(glyph[y * 640 + x]);
        }
    MESSAGE(covered << " pixels of labels ('frame', 'gi', 'propagate', 'lookup', the GI total), " << wrong
                    << " wrong");
    CHECK(covered > 100);
    CHECK(wrong == 0);
}

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
                const Image image = drawOverlay(*device, overlay, profiler, 320, height);
                const auto [first, last] = overlayRows(image);
                MESSAGE(backend.name << " " << height << " rows high: overlay from row " << first << " to "
                                     << last);
                CHECK(first == 8);                  // the backdrop, 4 pixels above the first bar
                CHECK(last <= int(height) - 8);     // and as far from the bottom
                CHECK(last >= int(height) * 2 / 3); // the rows use the height they have
            }
            device.expectSilent();
        }
    }
}
