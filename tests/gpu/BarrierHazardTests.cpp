// Barriers only where a hazard is (issue 46): frames whose commands depend on each other with
// nothing between them, so a missing barrier shows as wrong values read back, and as a hazard that
// synchronization validation reports (TestDevice fails on any message). Every backend, with the
// RHI's barriers and with the conservative ones.
#include "RhiScenarios.h"
#include "TestShaders.h"

#include "../support/TestDevice.h"
#include "rhi/Error.h"

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

constexpr uint32_t kVolumeTexels = kVolumeSize * kVolumeSize * kVolumeSize;

// Runs `body` on a device of every selected backend, once with each barrier rule, and on Vulkan
// with its textures in the layout of each use as well as in GENERAL (unified layouts, which a CPU
// device has): render passes then begin behind their own layout moves.
template <typename Body> void inEveryBarrierMode(Body body) {
    enum Mode { kAtHazards, kConservative, kLayoutsPerUse };
    static const char* const kNames[] = {"", ", conservative barriers", ", layouts per use"};
    for (const auto& backend : selectedBackends()) {
        for (const Mode mode : {kAtHazards, kConservative, kLayoutsPerUse}) {
            if (mode == kLayoutsPerUse && backend.kind != rhi::BackendKind::Vulkan) continue;
            SUBCASE((backend.name + kNames[mode]).c_str()) {
                rhi::DeviceConfig base;
                base.conservativeBarriers = mode == kConservative;
                if (mode == kLayoutsPerUse) base.unifiedImageLayouts = false;
                TestDevice device(backend, base);
                body(*device);
                device.expectSilent();
            }
        }
    }
}

rhi::TextureDesc volumeDesc(uint32_t usage, const char* name) {
    return {rhi::TextureKind::Tex3D,
            rhi::Format::RGBA16F,
            kVolumeSize,
            kVolumeSize,
            kVolumeSize,
            1,
            usage,
            name,
            "test"};
}

// A 16x16 RGBA16F render target, sampled, and (`storage`) a storage image: one that stays in one
// layout (Vulkan's GENERAL), so that no layout move orders the passes around it, only the RHI's
// barriers.
constexpr uint32_t kTargetSize = 16;
rhi::TextureHandle createTarget(rhi::Device& device, bool storage, const char* name) {
    using namespace rhi;
    return device.createTexture(
        {TextureKind::Tex2D, Format::RGBA16F, kTargetSize, kTargetSize, 1, 1,
         kTextureColorTarget | kTextureSampled | kTextureTransfer | (storage ? kTextureStorage : 0u), name,
         "test"});
}

// A fullscreen triangle drawn into one RGBA16F target by `fragment`.
rhi::GraphicsPipelineHandle fullscreenPipeline(rhi::Device& device, const rhi::ShaderBinary& fragment,
                                               const char* name) {
    rhi::GraphicsPipelineDesc pd;
    pd.vertex = &shaders::fullscreen_vert;
    pd.fragment = &fragment;
    pd.colorFormats = {rhi::Format::RGBA16F};
    pd.debugName = name;
    return device.createPipeline(pd);
}

rhi::BufferHandle createResult(rhi::Device& device, const char* name) {
    return device.createBuffer({kVolumeTexels * 16ull, rhi::kBufferStorage | rhi::kBufferTransfer,
                                rhi::MemoryAccess::GpuOnly, name, "test"});
}

std::vector<glm::vec4> readResult(rhi::Device& device, rhi::BufferHandle buffer) {
    std::vector<glm::vec4> got(kVolumeTexels);
    device.readBuffer(buffer, 0, got.data(), kVolumeTexels * 16ull);
    return got;
}

bool near(glm::vec4 got, glm::vec4 want) {
    for (int c = 0; c < 4; ++c)
        if (std::fabs(got[c] - want[c]) > 2e-3f + 1e-3f * std::fabs(want[c])) return false;
    return true;
}

// Texels of a 32^3 volume read back (x fastest) that differ from want(x, y, z).
template <typename Want> uint32_t wrongTexels(const std::vector<glm::vec4>& got, Want want) {
    uint32_t bad = 0;
    for (uint32_t z = 0; z < kVolumeSize; ++z)
        for (uint32_t y = 0; y < kVolumeSize; ++y)
            for (uint32_t x = 0; x < kVolumeSize; ++x)
                if (!near(got[x + kVolumeSize * (y + kVolumeSize * z)], want(x, y, z))) ++bad;
    return bad;
}

} // namespace

TEST_CASE("rhi: a dispatch reads what the previous one wrote; a buffer is updated while read") {
    for (const auto& backend : selectedBackends()) {
        for (const bool conservative : {false, true}) {
            SUBCASE((backend.name + (conservative ? ", conservative barriers" : "")).c_str()) {
                rhi::DeviceConfig base;
                base.conservativeBarriers = conservative;
                TestDevice device(backend, base);
                using namespace rhi;
                const TextureDesc vd{TextureKind::Tex3D,
                                     Format::RGBA16F,
                                     kVolumeSize,
                                     kVolumeSize,
                                     kVolumeSize,
                                     1,
                                     kTextureStorage | kTextureSampled | kTextureTransfer,
                                     "volume",
                                     "test"};
                const TextureHandle first = device->createTexture(vd), second = device->createTexture(vd);
                const uint32_t count = kVolumeSize * kVolumeSize * kVolumeSize;
                const BufferHandle result =
                    device->createBuffer({count * 16ull, kBufferStorage | kBufferTransfer,
                                          MemoryAccess::GpuOnly, "result", "test"});
                const glm::vec4 scale{0.1f, 0.2f, 0.05f, 0.0f}, zero{0.0f};
                const BufferHandle params =
                    device->createBuffer({sizeof(scale), kBufferUniform | kBufferTransfer,
                                          MemoryAccess::GpuOnly, "params", "test"},
                                         &scale);
                const ComputePipelineHandle fill =
                    device->createPipeline(ComputePipelineDesc{&shaders::fill_volume_comp, "fill"});
                const ComputePipelineHandle sample =
                    device->createPipeline(ComputePipelineDesc{&shaders::sample_volume_comp, "sample"});
                const SamplerHandle point = device->createSampler({});

                CommandList& cmd = device->beginFrame();
                cmd.bindPipeline(fill); // writes `first` with `params`
                cmd.bindStorageImage(0, first);
                cmd.bindUniformBuffer(1, params);
                cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
                cmd.bindPipeline(sample); // reads `first` at once: read after write
                cmd.bindTexture(0, first, point);
                cmd.bindStorageBuffer(1, result);
                cmd.dispatch(count / 64);
                cmd.updateBuffer(params, 0, &zero, sizeof(zero)); // written after the first read it
                cmd.bindPipeline(fill);
                cmd.bindStorageImage(0, second);
                cmd.bindUniformBuffer(1, params);
                cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
                device->endFrame();
                device->waitIdle();

                std::vector<glm::vec4> got(count);
                device->readBuffer(result, 0, got.data(), count * 16ull);
                const Image zeroed = readImage(*device, second);
                uint32_t bad = 0;
                for (uint32_t z = 0; z < kVolumeSize; ++z)
                    for (uint32_t y = 0; y < kVolumeSize; ++y)
                        for (uint32_t x = 0; x < kVolumeSize; ++x) {
                            const glm::vec4 want = expectedVolumeTexel(x, y, z);
                            const glm::vec4 g = got[x + kVolumeSize * (y + kVolumeSize * z)];
                            const glm::vec4 w0{0.0f, 0.0f, float(int(x + 2 * y) - int(z)) / 64.0f, 1.0f};
                            const glm::vec4 g0 = zeroed.at(x, y, z);
                            for (int c = 0; c < 4; ++c) {
                                if (std::fabs(g[c] - want[c]) > 2e-3f + 1e-3f * std::fabs(want[c])) ++bad;
                                if (std::fabs(g0[c] - w0[c]) > 2e-3f) ++bad;
                            }
                        }
                CHECK(bad == 0);
                device->destroy(fill);
                device->destroy(sample);
                device->destroy(point);
                device->destroy(params);
                device->destroy(result);
                device->destroy(first);
                device->destroy(second);
                device.expectSilent();
            }
        }
    }
}

// The fill and sample kernels over a volume, with their parameters (fill_volume.comp's scale)
// and sampler: fill() writes expectedVolumeTexel into a storage volume, sample() reads a volume
// into a result buffer.
struct VolumeKernels {
    rhi::Device& device;
    const glm::vec4 scale{0.1f, 0.2f, 0.05f, 0.0f};
    rhi::BufferHandle params = device.createBuffer({sizeof(scale), rhi::kBufferUniform | rhi::kBufferTransfer,
                                                    rhi::MemoryAccess::GpuOnly, "params", "test"},
                                                   &scale);
    rhi::ComputePipelineHandle fillPipeline =
        device.createPipeline(rhi::ComputePipelineDesc{&shaders::fill_volume_comp, "fill"});
    rhi::ComputePipelineHandle samplePipeline =
        device.createPipeline(rhi::ComputePipelineDesc{&shaders::sample_volume_comp, "sample"});
    rhi::SamplerHandle point = device.createSampler({});

    explicit VolumeKernels(rhi::Device& d) : device(d) {}
    ~VolumeKernels() {
        device.destroy(fillPipeline);
        device.destroy(samplePipeline);
        device.destroy(point);
        device.destroy(params);
    }
    VolumeKernels(const VolumeKernels&) = delete;
    VolumeKernels& operator=(const VolumeKernels&) = delete;
    void fill(rhi::CommandList& cmd, rhi::TextureHandle t) const {
        cmd.bindPipeline(fillPipeline);
        cmd.bindStorageImage(0, t);
        cmd.bindUniformBuffer(1, params);
        cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
    }
    void sample(rhi::CommandList& cmd, rhi::TextureHandle t, rhi::BufferHandle result) const {
        cmd.bindPipeline(samplePipeline);
        cmd.bindTexture(0, t, point);
        cmd.bindStorageBuffer(1, result);
        cmd.dispatch(kVolumeTexels / 64);
    }
};

TEST_CASE("rhi: a clear and a copy are read by the next dispatch; a copy's source is cleared after it") {
    inEveryBarrierMode([](rhi::Device& device) {
        using namespace rhi;
        const uint32_t storage = kTextureStorage | kTextureSampled | kTextureTransfer;
        const TextureHandle first = device.createTexture(volumeDesc(storage, "first"));
        const TextureHandle second = device.createTexture(volumeDesc(storage, "second"));
        // Not a storage image: the copy moves it (TRANSFER_DST and back on Vulkan).
        const TextureHandle third =
            device.createTexture(volumeDesc(kTextureSampled | kTextureTransfer, "third"));
        const BufferHandle cleared = createResult(device, "cleared"), copied = createResult(device, "copied"),
                           zeroed = createResult(device, "zeroed");
        const glm::vec4 clearValue{0.5f, -0.25f, 2.0f, 1.0f};
        const glm::vec4 marker{7.0f, 8.0f, 9.0f, 10.0f};
        const VolumeKernels kernels(device);
        const auto fillVolume = [&](CommandList& cmd, TextureHandle t) { kernels.fill(cmd, t); };
        const auto sampleVolume = [&](CommandList& cmd, TextureHandle t, BufferHandle result) {
            kernels.sample(cmd, t, result);
        };

        CommandList& cmd = device.beginFrame();
        fillVolume(cmd, first);
        cmd.clearTexture(first, {clearValue.x, clearValue.y, clearValue.z, clearValue.w}); // after the fill
        sampleVolume(cmd, first, cleared);                                                 // reads the clear
        fillVolume(cmd, second);
        cmd.copyTexture(second, third);                       // reads what the fill wrote
        cmd.clearTexture(second, {0, 0, 0, 0});               // writes what the copy read
        sampleVolume(cmd, third, copied);                     // reads the copy
        sampleVolume(cmd, second, zeroed);                    // reads the clear
        cmd.updateBuffer(zeroed, 0, &marker, sizeof(marker)); // writes over what the dispatch wrote
        device.endFrame();
        device.waitIdle();

        CHECK(wrongTexels(readResult(device, cleared),
                          [&](uint32_t, uint32_t, uint32_t) { return clearValue; }) == 0);
        CHECK(wrongTexels(readResult(device, copied), expectedVolumeTexel) == 0);
        CHECK(wrongTexels(readResult(device, zeroed), [&](uint32_t x, uint32_t y, uint32_t z) {
                  return x + y + z == 0 ? marker : glm::vec4(0.0f);
              }) == 0);
        for (const BufferHandle b : {cleared, copied, zeroed})
            device.destroy(b);
        for (const TextureHandle t : {first, second, third})
            device.destroy(t);
    });
}

TEST_CASE("rhi: copies behind one barrier read what dispatches wrote, and are read after") {
    inEveryBarrierMode([](rhi::Device& device) {
        using namespace rhi;
        const TextureHandle a = device.createTexture(volumeDesc(kTextureStorage | kTextureTransfer, "a"));
        const TextureHandle b = device.createTexture(volumeDesc(kTextureStorage | kTextureTransfer, "b"));
        const TextureHandle c = device.createTexture(volumeDesc(kTextureSampled | kTextureTransfer, "c"));
        const TextureHandle d = device.createTexture(volumeDesc(kTextureSampled | kTextureTransfer, "d"));
        const BufferHandle fromC = createResult(device, "from c"), fromD = createResult(device, "from d");
        const VolumeKernels kernels(device);

        CommandList& cmd = device.beginFrame();
        kernels.fill(cmd, a);
        kernels.fill(cmd, b);
        const std::array<TextureCopy, 2> copies{{{a, c}, {b, d}}};
        cmd.copyTextures(copies); // both read what the fills wrote
        kernels.sample(cmd, c, fromC);
        kernels.sample(cmd, d, fromD);
        device.endFrame();
        device.waitIdle();
        CHECK(wrongTexels(readResult(device, fromC), expectedVolumeTexel) == 0);
        CHECK(wrongTexels(readResult(device, fromD), expectedVolumeTexel) == 0);

        // More than kMaxCopies in one call, or a copy onto itself, is refused.
        CommandList& refused = device.beginFrame();
        std::array<TextureCopy, TextureCopy::kMaxCopies + 1> many;
        many.fill({a, c});
        CHECK_THROWS_AS(refused.copyTextures(many), rhi::Error);
        CHECK_THROWS_WITH_AS(refused.copyTexture(a, a),
                             "copyTexture: source and destination are the same texture", Error);
        device.endFrame();
        device.waitIdle();
        for (const BufferHandle buffer : {fromC, fromD})
            device.destroy(buffer);
        for (const TextureHandle t : {a, b, c, d})
            device.destroy(t);
    });
}

TEST_CASE("rhi: a render target is sampled by the next pass; a dispatch reads what a pass drew") {
    inEveryBarrierMode([](rhi::Device& device) {
        using namespace rhi;
        constexpr uint32_t kSize = kTargetSize, kSlice = 5;
        const TextureHandle drawn = createTarget(device, true, "drawn");
        const TextureHandle summed = createTarget(device, false, "summed");
        const TextureHandle volume = device.createTexture(
            volumeDesc(kTextureStorage | kTextureColorTarget | kTextureSampled | kTextureTransfer, "volume"));
        const BufferHandle result = createResult(device, "result");
        const glm::vec4 scale{0.1f, 0.2f, 0.05f, 0.0f};
        const BufferHandle params = device.createBuffer(
            {sizeof(scale), kBufferUniform | kBufferTransfer, MemoryAccess::GpuOnly, "params", "test"},
            &scale);
        const GraphicsPipelineHandle constant =
            fullscreenPipeline(device, shaders::constant_frag, "constant");
        const GraphicsPipelineHandle sampleTarget =
            fullscreenPipeline(device, shaders::sample_target_frag, "sample target");
        const ComputePipelineHandle fill =
            device.createPipeline(ComputePipelineDesc{&shaders::fill_volume_comp, "fill"});
        const ComputePipelineHandle sample =
            device.createPipeline(ComputePipelineDesc{&shaders::sample_volume_comp, "sample"});
        const SamplerHandle point = device.createSampler({});
        const glm::vec4 a{0.25f, 0.5f, 0.75f, 1.0f}, b{1.0f, 2.0f, 3.0f, 4.0f}, c{-1.0f, 0.5f, 0.0f, 2.0f};
        const auto pass = [&](TextureHandle t, uint32_t layer, LoadOp load) {
            RenderPassDesc rp;
            rp.colors[0] = {t, 0, layer, load};
            rp.colorCount = 1;
            rp.debugName = "hazard pass";
            return rp;
        };

        CommandList& cmd = device.beginFrame();
        cmd.clearTexture(drawn, {1, 1, 1, 1});
        cmd.beginRenderPass(pass(drawn, 0, LoadOp::Load)); // loads what the clear wrote
        cmd.bindPipeline(constant);
        cmd.pushUniforms(0, &a, sizeof(a));
        cmd.draw(3);
        cmd.endRenderPass();
        cmd.beginRenderPass(pass(summed, 0, LoadOp::Clear)); // samples what the pass before drew
        cmd.bindPipeline(sampleTarget);
        cmd.pushUniforms(0, &b, sizeof(b));
        cmd.bindTexture(1, drawn, point);
        cmd.draw(3);
        cmd.endRenderPass();
        cmd.beginRenderPass(pass(drawn, 0, LoadOp::Load)); // draws over what the pass before sampled
        cmd.bindPipeline(constant);
        cmd.pushUniforms(0, &c, sizeof(c));
        cmd.draw(3);
        cmd.endRenderPass();
        cmd.bindPipeline(fill);
        cmd.bindStorageImage(0, volume);
        cmd.bindUniformBuffer(1, params);
        cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
        cmd.beginRenderPass(pass(volume, kSlice, LoadOp::Load)); // draws over one slice of the fill
        cmd.bindPipeline(constant);
        cmd.pushUniforms(0, &a, sizeof(a));
        cmd.draw(3);
        cmd.endRenderPass();
        cmd.bindPipeline(sample); // reads what the fill and the pass wrote
        cmd.bindTexture(0, volume, point);
        cmd.bindStorageBuffer(1, result);
        cmd.dispatch(kVolumeTexels / 64);
        device.endFrame();
        device.waitIdle();

        const Image drawnImage = readImage(device, drawn), summedImage = readImage(device, summed);
        uint32_t bad = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x)
                bad += (near(drawnImage.at(x, y), c) ? 0 : 1) + (near(summedImage.at(x, y), a + b) ? 0 : 1);
        CHECK(bad == 0);
        CHECK(wrongTexels(readResult(device, result), [&](uint32_t x, uint32_t y, uint32_t z) {
                  return z == kSlice ? a : expectedVolumeTexel(x, y, z);
              }) == 0);
        for (const GraphicsPipelineHandle p : {constant, sampleTarget})
            device.destroy(p);
        for (const ComputePipelineHandle p : {fill, sample})
            device.destroy(p);
        device.destroy(point);
        device.destroy(params);
        device.destroy(result);
        for (const TextureHandle t : {drawn, summed, volume})
            device.destroy(t);
    });
}

TEST_CASE("rhi: a later draw of a pass samples what a clear before the pass wrote") {
    inEveryBarrierMode([](rhi::Device& device) {
        using namespace rhi;
        constexpr uint32_t kSize = kTargetSize;
        const TextureHandle cleared = createTarget(device, true, "cleared");
        const TextureHandle quiet = createTarget(device, true, "quiet");
        const TextureHandle summed = createTarget(device, false, "summed");
        const GraphicsPipelineHandle sampleTarget =
            fullscreenPipeline(device, shaders::sample_target_frag, "sample target");
        const SamplerHandle point = device.createSampler({});
        const glm::vec4 q{0.5f, 0.25f, 1.0f, 1.0f}, v{2.0f, 3.0f, 4.0f, 5.0f}, b{1.0f, 2.0f, 3.0f, 4.0f};

        device.beginFrame().clearTexture(quiet, {q.x, q.y, q.z, q.w});
        device.endFrame();
        CommandList& cmd = device.beginFrame();
        cmd.clearTexture(cleared, {v.x, v.y, v.z, v.w});
        RenderPassDesc rp;
        rp.colors[0] = {summed, 0, 0, LoadOp::Clear};
        rp.colorCount = 1;
        rp.debugName = "two draws";
        cmd.beginRenderPass(rp);
        cmd.bindPipeline(sampleTarget);
        cmd.pushUniforms(0, &b, sizeof(b));
        cmd.bindTexture(1, quiet, point); // nothing of this frame touched it
        cmd.draw(3);
        cmd.setScissor(0, 0, kSize / 2, kSize);
        cmd.bindTexture(1, cleared, point); // the clear must be ordered before this draw
        cmd.draw(3);
        cmd.endRenderPass();
        device.endFrame();
        device.waitIdle();

        // Left: the second draw, over what the clear wrote; right: the first draw's, kept.
        const Image image = readImage(device, summed);
        uint32_t bad = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x)
                bad += near(image.at(x, y), (x < kSize / 2 ? v : q) + b) ? 0 : 1;
        CHECK(bad == 0);
        device.destroy(sampleTarget);
        device.destroy(point);
        for (const TextureHandle t : {cleared, quiet, summed})
            device.destroy(t);
    });
}
