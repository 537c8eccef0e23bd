// One test body per feature, run against every selected backend (Vulkan, GL-EGL, GL-OSMesa), each
// checking real pixels read back from the device, with validation on and required to stay silent.
#include "RhiScenarios.h"
#include "TestShaders.h"

#include "../support/TestDevice.h"

#include "rhi/Error.h"

#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <string>

using namespace lpv;
using namespace lpv::test;

namespace {

bool near(glm::vec4 a, glm::vec4 b, float tol) {
    for (int c = 0; c < 4; ++c)
        if (std::fabs(a[c] - b[c]) > tol) return false;
    return true;
}

} // namespace

TEST_CASE("rhi: clear a render target") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            const TextureHandle t =
                device->createTexture({TextureKind::Tex2D, Format::RGBA8Unorm, 8, 4, 1, 1,
                                       kTextureColorTarget | kTextureTransfer, "clear", "test"});
            CommandList& cmd = device->beginFrame();
            RenderPassDesc pass;
            pass.colors[0] = {t, 0, 0, LoadOp::Clear, {0.2f, 0.4f, 0.6f, 1.0f}};
            pass.colorCount = 1;
            cmd.beginRenderPass(pass);
            cmd.endRenderPass();
            device->endFrame();
            device->waitIdle();
            const Image img = readImage(*device, t);
            for (const glm::vec4& texel : img.texels)
                REQUIRE_MESSAGE(near(texel, {0.2f, 0.4f, 0.6f, 1.0f}, 1.0f / 255.0f), describe(texel));
            device->destroy(t);
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: indexed triangles into two color targets and depth") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const MrtImages img = renderIndexedMrt(*device);
            const float tol = 1.0f / 255.0f + 1e-4f;
            // Only triangle A (red, z 0.5) in the upper left.
            CHECK_MESSAGE(near(img.color.at(4, 4), {1, 0, 0, 1}, tol), describe(img.color.at(4, 4)));
            CHECK(img.depth.at(4, 4).x == doctest::Approx(0.5f).epsilon(1e-5));
            CHECK_MESSAGE(near(img.second.at(4, 4), kMrtTint, 1e-3f), describe(img.second.at(4, 4)));
            // Triangle B (green, z 0.25, drawn first) wins the depth test where both cover.
            CHECK_MESSAGE(near(img.color.at(40, 4), {0, 1, 0, 0.5f}, tol), describe(img.color.at(40, 4)));
            CHECK(img.depth.at(40, 4).x == doctest::Approx(0.25f).epsilon(1e-5));
            CHECK_MESSAGE(near(img.second.at(40, 4), kMrtTint * 0.5f, 1e-3f), describe(img.second.at(40, 4)));
            // NDC y=-1 is row 0: the bottom rows of the right half are uncovered.
            CHECK_MESSAGE(near(img.color.at(40, 60), kMrtClear, tol), describe(img.color.at(40, 60)));
            CHECK(img.depth.at(60, 60).x == doctest::Approx(1.0f));
            CHECK_MESSAGE(near(img.second.at(60, 60), {0, 0, 0, 0}, 1e-6f), describe(img.second.at(60, 60)));
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: compute shader writes a 32^3 RGBA16F volume matching the CPU") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const Image volume = fillVolume(*device);
            REQUIRE(volume.texels.size() == kVolumeSize * kVolumeSize * kVolumeSize);
            // Tolerance: half precision keeps 11 significant bits (relative 2^-11 ~ 4.9e-4) plus the
            // GPU's sin/cos error; 2e-3 absolute + 1e-3 relative covers both, nothing more.
            uint32_t bad = 0;
            float worst = 0.0f;
            for (uint32_t z = 0; z < kVolumeSize; ++z)
                for (uint32_t y = 0; y < kVolumeSize; ++y)
                    for (uint32_t x = 0; x < kVolumeSize; ++x) {
                        const glm::vec4 want = expectedVolumeTexel(x, y, z);
                        const glm::vec4 got = volume.at(x, y, z);
                        for (int c = 0; c < 4; ++c) {
                            const float err = std::fabs(got[c] - want[c]);
                            worst = std::max(worst, err);
                            if (err > 2e-3f + 1e-3f * std::fabs(want[c])) ++bad;
                        }
                    }
            CHECK_MESSAGE(bad == 0, "worst absolute error " << worst);
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: additive blending accumulates") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const Image img = additiveBlend(*device);
            const glm::vec4 want = kBlendClear + 2.0f * kBlendColor;
            for (const glm::vec4& texel : img.texels)
                REQUIRE_MESSAGE(near(texel, want, 1e-3f), describe(texel));
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: a long point list, some points outside the clip volume") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const Image img = drawPoints(*device);
            for (uint32_t y = 0; y < 16; ++y)
                for (uint32_t x = 0; x < 16; ++x)
                    REQUIRE_MESSAGE(near(img.at(x, y), expectedPointTexel(x, y), 1e-3f),
                                    "at " << x << "," << y << " " << describe(img.at(x, y)));
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: one indirect multi-draw draws each of its draws with its own first instance") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            REQUIRE(device->caps().multiDrawIndirect);
            const MultiDrawResult r = multiDrawQuads(*device);
            float want[4] = {0, 0, 0, 0};
            for (const auto& [quad, instance] : kMultiDraws)
                want[quad] = float(kMultiDrawValues[instance]);
            for (uint32_t y = 0; y < 4; ++y)
                for (uint32_t x = 0; x < 16; ++x)
                    REQUIRE_MESSAGE(
                        near(r.image.at(x, y), {want[x / 4], 0, 0, want[x / 4] > 0 ? 1.0f : 0.0f}, 1e-3f),
                        "at " << x << "," << y << " " << describe(r.image.at(x, y)));
            // One call, as the API sees it.
            CHECK(r.counts.drawsIndexed == 1);
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: a fragment shader exports the stencil, and masked stencil tests select its fields") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            if (!device->caps().shaderStencilExport) {
                MESSAGE(backend.name << ": no shader stencil export, skipped");
                continue;
            }
            const Image img = drawStencilFields(*device);
            uint32_t covered[3] = {0, 0, 0};
            for (uint32_t y = 0; y < 16; ++y)
                for (uint32_t x = 0; x < 16; ++x) {
                    const glm::vec4 want = expectedStencilTexel(x, y);
                    for (int i = 0; i < 3; ++i)
                        covered[i] += want[i] > 0.0f ? 1 : 0;
                    REQUIRE_MESSAGE(near(img.at(x, y), want, 1e-3f),
                                    "at " << x << "," << y << " " << describe(img.at(x, y)));
                }
            // Each draw matched some pixels and missed others: the first x & 3 == 2 (3 exported
            // columns), the second y & 3 == 1 in the exported columns and all of the cleared ones,
            // the third the cleared columns and the exported pixels whose stencil equals the clear.
            CHECK(covered[0] == 3 * 16);
            CHECK(covered[1] == 12 * 4 + 4 * 16);
            CHECK(covered[2] == 4 * 16 + 3 * 4);
            device.expectSilent();
        }
    }
}

// A helper, not the subcase's body: a return from a subcase where a device lacks the capability
// would make doctest skip the later subcases of the loop.
static void checkLayeredPoints(TestDevice& device) {
    const Image img = drawLayeredPoints(*device);
    for (uint32_t z = 0; z < kLayeredSize; ++z)
        for (uint32_t y = 0; y < kLayeredSize; ++y)
            for (uint32_t x = 0; x < kLayeredSize; ++x)
                REQUIRE_MESSAGE(near(img.at(x, y, z), expectedLayeredTexel(x, y, z), 1e-3f),
                                "at " << x << "," << y << "," << z << " " << describe(img.at(x, y, z)));
    device.expectSilent();
}

TEST_CASE("rhi: one layered draw fills every slice of a 3D texture, each point picking its own") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            if (device->caps().vertexShaderLayer)
                checkLayeredPoints(device);
            else
                MESSAGE("backend " << backend.name
                                   << " cannot pick the layer in a vertex shader; nothing to check");
        }
    }
}

TEST_CASE("rhi: render into one slice of a 3D texture, then sample it from compute") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const InjectionResult r = injectIntoSlice(*device);
            for (uint32_t z = 0; z < kInjectSize; ++z) {
                const glm::vec4 want = z == kInjectSlice ? 2.0f * kBlendColor : glm::vec4(0.0f);
                for (uint32_t y = 0; y < kInjectSize; ++y)
                    for (uint32_t x = 0; x < kInjectSize; ++x) {
                        const size_t i = (size_t(z) * kInjectSize + y) * kInjectSize + x;
                        REQUIRE_MESSAGE(near(r.readback.at(x, y, z), want, 1e-3f),
                                        "readback at " << x << "," << y << "," << z << " "
                                                       << describe(r.readback.at(x, y, z)));
                        REQUIRE_MESSAGE(near(r.sampledReads[i], want, 1e-3f),
                                        "sampled at " << x << "," << y << "," << z << " "
                                                      << describe(r.sampledReads[i]));
                    }
            }
            device.expectSilent();
        }
    }
}

// A helper for the same reason as checkLayeredPoints.
static void checkTimestamps(TestDevice& device, const std::string& backendName) {
    using namespace rhi;
    REQUIRE(device->caps().maxTimestampsPerFrame >= 2);
    const TextureHandle volume = device->createTexture(
        {TextureKind::Tex3D, Format::RGBA16F, 32, 32, 32, 1, kTextureStorage, "timed volume", "test"});
    const ComputePipelineHandle pipeline =
        device->createPipeline(ComputePipelineDesc{&shaders::fill_volume_comp, "timed"});
    const glm::vec4 scale{0.1f, 0.2f, 0.05f, 0.0f};

    CommandList& cmd = device->beginFrame();
    const uint64_t timedFrame = device->frameIndex();
    cmd.writeTimestamp(0);
    cmd.bindPipeline(pipeline);
    cmd.bindStorageImage(0, volume);
    cmd.pushUniforms(1, &scale, sizeof(scale));
    cmd.dispatch(4, 4, 32);
    cmd.writeTimestamp(1);
    device->endFrame();

    // Keep running empty frames until the results show up; beginFrame() waits only for the
    // frame slot being reused, so results must appear within framesInFlight frames.
    uint64_t ts[2] = {0, 0};
    bool ready = false;
    for (uint32_t i = 0; i <= device->caps().framesInFlight && !ready; ++i) {
        ready = device->readTimestamps(timedFrame, ts);
        if (!ready) {
            device->beginFrame();
            device->endFrame();
        }
    }
    REQUIRE(ready);
    CHECK(ts[0] != 0);
    CHECK(ts[1] > ts[0]);
    MESSAGE(backendName << ": 32^3 dispatch took " << double(ts[1] - ts[0]) / 1e6 << " ms ("
                        << timestampSourceName(device->caps().timestampSource) << ")");
    device->waitIdle();
    device->destroy(pipeline);
    device->destroy(volume);
    device.expectSilent();
}

TEST_CASE("rhi: timestamps are ordered and read back frames later without waiting") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            INFO("timestamp source: " << rhi::timestampSourceName(device->caps().timestampSource));
            if (device->caps().timestampSource != rhi::TimestampSource::None)
                checkTimestamps(device, backend.name);
            else
                MESSAGE("backend " << backend.name << " has no timestamps; nothing to check");
        }
    }
}

TEST_CASE("rhi: storage images bind below Caps::storageImageBindings, which a device config lowers") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            using namespace rhi;
            for (const std::optional<uint32_t> configured :
                 {std::optional<uint32_t>{}, std::optional<uint32_t>{8}}) {
                DeviceConfig config;
                config.storageImageBindings = configured;
                TestDevice device(backend, config);
                const uint32_t limit = device->caps().storageImageBindings;
                INFO(backend.name << ": " << limit << " storage image bindings");
                CHECK(limit >= kPortableStorageImageBindings);
                if (configured) CHECK(limit == *configured);
                const TextureHandle volume =
                    device->createTexture({TextureKind::Tex3D, Format::RGBA16F, 4, 4, 4, 1, kTextureStorage,
                                           "bound volume", "test"});
                const ComputePipelineHandle pipeline =
                    device->createPipeline(ComputePipelineDesc{&shaders::fill_volume_comp, "binding rule"});
                CommandList& cmd = device->beginFrame();
                cmd.bindPipeline(pipeline);
                CHECK_NOTHROW(cmd.bindStorageImage(limit - 1, volume));
                // At the device's own limit (32 on Mesa) the command list's binding slots end too.
                CHECK_THROWS_AS(cmd.bindStorageImage(limit, volume), Error);
                if (configured) {
                    const std::string expected =
                        "storage image binding " + std::to_string(limit) + " is not below";
                    CHECK_THROWS_WITH_AS(cmd.bindStorageImage(limit, volume),
                                         doctest::Contains(expected.c_str()), Error);
                }
                device->endFrame();
                device->waitIdle();
                // A shader with a storage image at binding 8 is refused at creation where the limit
                // is 8 (Vulkan's reflection, GL's link-time check or its compiler), made otherwise.
                const ComputePipelineDesc past{&shaders::image_binding_8_comp, "image at binding 8"};
                if (limit > 8)
                    device->destroy(device->createPipeline(past));
                else
                    CHECK_THROWS_WITH_AS(device->createPipeline(past), doctest::Contains("binding 8"), Error);
                device->destroy(pipeline);
                device->destroy(volume);
                device.expectSilent();
            }
        }
    }
}

TEST_CASE("rhi: a HostRead buffer shows what shaders wrote once beginFrame() has waited for that frame") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            // One region per frame in flight, at an offset any device's storage alignment allows.
            constexpr uint64_t kRegion = 256;
            const uint32_t regions = device->caps().framesInFlight;
            const BufferHandle report = device->createBuffer(
                {kRegion * regions, kBufferStorage, MemoryAccess::HostRead, "report back", "test"});
            const ComputePipelineHandle pipeline =
                device->createPipeline(ComputePipelineDesc{&shaders::report_back_comp, "report back"});
            auto* bytes = static_cast<std::byte*>(device->mapped(report));
            REQUIRE(bytes != nullptr);
            constexpr uint32_t kGroups = 5, kInvocations = kGroups * 64;
            uint32_t checked = 0;
            for (uint32_t frame = 1; frame <= 3 * regions + 1; ++frame) {
                CommandList& cmd = device->beginFrame();
                REQUIRE(device->frameIndex() == frame);
                auto* region = reinterpret_cast<uint32_t*>(bytes + kRegion * (frame % regions));
                // This region was written framesInFlight frames ago, whose end beginFrame() waited for.
                if (frame > regions) {
                    const uint32_t scale = frame - regions;
                    CHECK(region[0] == kInvocations);
                    CHECK(region[1] == (kInvocations - 1) * scale);
                    ++checked;
                }
                region[0] = region[1] = 0;
                const glm::uvec4 params{frame, 0, 0, 0};
                cmd.bindPipeline(pipeline);
                cmd.bindStorageBuffer(0, report, kRegion * (frame % regions), kRegion);
                cmd.pushUniforms(1, &params, sizeof(params));
                cmd.dispatch(kGroups);
                device->endFrame();
            }
            CHECK(checked == 2 * regions + 1);
            device->waitIdle();
            device->destroy(pipeline);
            device->destroy(report);
            device.expectSilent();
        }
    }
}

TEST_CASE("rhi: allocation record follows creation and destruction on a real device") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            using namespace rhi;
            const uint64_t before = device->allocations().bytesIn("test");
            const TextureHandle t = device->createTexture(
                {TextureKind::Tex3D, Format::RGBA16F, 32, 32, 32, 1, kTextureStorage, "lpv red", "test.lpv"});
            CHECK(device->allocations().bytesIn("test") - before >= 32u * 32u * 32u * 8u);
            device->destroy(t);
            CHECK(device->allocations().bytesIn("test") == before);
            CHECK_THROWS_AS(device->desc(t), rhi::Error);
            device.expectSilent();
        }
    }
}
