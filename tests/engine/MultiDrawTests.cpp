// engine::MultiDraw's ring on the null device: where each frame's commands go, and the one growth a
// frame that draws more than its room makes.
#include "engine/render/MultiDraw.h"

#include "rhi/Device.h"

#include <doctest/doctest.h>

#include <memory>

using namespace lpv;

namespace {

constexpr const char* kCategory = "test.draw_commands";
constexpr uint64_t kCommand = sizeof(rhi::DrawIndexedIndirectCommand);

// One frame that adds `draws` draws in `calls` equal multi-draws into a 4x4 target; returns the
// frame's indexed draw calls.
uint32_t frame(rhi::Device& device, engine::MultiDraw& multiDraw, uint32_t draws, uint32_t calls = 1) {
    const rhi::TextureHandle target =
        device.createTexture({rhi::TextureKind::Tex2D, rhi::Format::RGBA8Unorm, 4, 4, 1, 1,
                              rhi::kTextureColorTarget, "target", "test"});
    rhi::CommandList& cmd = device.beginFrame();
    rhi::RenderPassDesc pass;
    pass.colors[0] = {target};
    pass.colorCount = 1;
    cmd.beginRenderPass(pass);
    for (uint32_t c = 0; c < calls; ++c) {
        for (uint32_t k = 0; k < draws / calls; ++k)
            multiDraw.add({3 * k, 3, 0.0f}, k);
        multiDraw.draw(cmd);
    }
    cmd.endRenderPass();
    device.endFrame();
    device.destroy(target);
    return device.frameCounters().drawsIndexed;
}

} // namespace

TEST_CASE(
    "render: a multi-draw ring grows once for a frame that draws more, and frees the old buffer later") {
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    const std::unique_ptr<rhi::Device> device = rhi::createDevice(config);
    const uint64_t frames = device->caps().framesInFlight;
    {
        engine::MultiDraw multiDraw(*device, "test", kCategory);
        multiDraw.reserve(100);
        CHECK(device->allocations().bytesIn(kCategory) == 100 * frames * kCommand);
        // Within its room: one call a batch, no new buffer.
        CHECK(frame(*device, multiDraw, 100, 2) == 2);
        CHECK(device->allocations().bytesIn(kCategory) == 100 * frames * kCommand);
        // Twice its room in one frame (an RSM drawn for two cascades): it grows to 200, keeping the
        // old buffer, which this frame's first call reads, until no frame can.
        CHECK(frame(*device, multiDraw, 200, 2) == 2);
        CHECK(device->allocations().bytesIn(kCategory) == (100 + 200) * frames * kCommand);
        for (uint64_t f = 0; f < frames; ++f)
            CHECK(frame(*device, multiDraw, 200, 2) == 2);
        CHECK(device->allocations().bytesIn(kCategory) == 200 * frames * kCommand);
        // Now a frame of 200 fits: no more buffers; reserve() below the room changes nothing.
        multiDraw.reserve(50);
        CHECK(frame(*device, multiDraw, 200) == 1);
        CHECK(device->allocations().bytesIn(kCategory) == 200 * frames * kCommand);
    }
    CHECK(device->allocations().bytesIn(kCategory) == 0);
}

TEST_CASE("render: without multi-draws a batch goes out one indexed draw each") {
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    config.multiDrawIndirect = false;
    const std::unique_ptr<rhi::Device> device = rhi::createDevice(config);
    engine::MultiDraw multiDraw(*device, "test", kCategory);
    multiDraw.reserve(6);
    CHECK(frame(*device, multiDraw, 6, 2) == 6);
}
