// The windowed path: a GLFW window on each backend presenting frames. ctest runs this under
// xvfb-run, so it needs no real display.
#include "../support/TestDevice.h"

#include "platforms/Window.h"
#include "rhi/Device.h"

#include <doctest/doctest.h>

using namespace lpv;

TEST_CASE("window: each backend opens a window and presents frames") {
    REQUIRE_MESSAGE(platforms::Window::displayAvailable(), "no X display (run under xvfb-run)");
    for (const rhi::BackendKind kind : {rhi::BackendKind::Vulkan, rhi::BackendKind::OpenGL}) {
        SUBCASE(std::string(rhi::backendName(kind)).c_str()) {
            platforms::Window window({320, 180, "LPV window test", true});
            std::vector<std::string> messages;
            rhi::DeviceConfig config;
            config.backend = kind;
            config.allowFallback = false;
            config.window = &window;
            config.validation = true;
            config.onDebugMessage = [&](const rhi::DebugMessage& m) {
                if (m.severity != rhi::DebugSeverity::Info) messages.push_back(m.text);
            };
            {
                auto device = rhi::createDevice(config);
                CHECK(device->backend() == kind);
                CHECK(device->caps().presentation);
                using namespace rhi;
                const TextureHandle frame = device->createTexture(
                    {TextureKind::Tex2D, Format::RGBA8Unorm, 160, 90, 1, 1,
                     kTextureColorTarget | kTextureSampled | kTextureTransfer, "presented", "test"});
                for (int i = 0; i < 6; ++i) {
                    window.pollEvents();
                    CommandList& cmd = device->beginFrame();
                    RenderPassDesc pass;
                    pass.colors[0] = {frame, 0, 0, LoadOp::Clear, {float(i) / 6.0f, 0.5f, 0.2f, 1.0f}};
                    pass.colorCount = 1;
                    cmd.beginRenderPass(pass);
                    cmd.endRenderPass();
                    device->endFrame(frame);
                }
                CHECK(device->frameIndex() == 6);
                device->waitIdle();
                device->destroy(frame);
            }
            for (const auto& m : messages)
                FAIL_CHECK("debug message: " << m);
        }
    }
}
