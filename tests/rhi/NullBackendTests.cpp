// Front-end behaviour of the RHI without a GPU: handle lifetime, allocation accounting, frame and
// argument checks, backend names.
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <doctest/doctest.h>

#include <string>

using namespace lpv::rhi;

namespace {
std::unique_ptr<Device> nullDevice(bool vertexShaderLayer = true) {
    DeviceConfig config;
    config.backend = BackendKind::Null;
    config.vertexShaderLayer = vertexShaderLayer;
    return createDevice(config);
}

std::string errorOf(auto&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}
} // namespace

TEST_CASE("null backend: a destroyed handle is caught, not reused") {
    auto device = nullDevice();
    const TextureHandle a = device->createTexture(
        {TextureKind::Tex2D, Format::RGBA8Unorm, 4, 4, 1, 1, kTextureSampled, "a", "test"});
    device->destroy(a);
    // The slot is reused by the next texture, with a new generation.
    const TextureHandle b = device->createTexture(
        {TextureKind::Tex2D, Format::RGBA8Unorm, 4, 4, 1, 1, kTextureSampled, "b", "test"});
    CHECK(a.index() == b.index());
    CHECK(a.generation() != b.generation());
    CHECK(device->desc(b).debugName == "b");
    const std::string message = errorOf([&] { device->desc(a); });
    CHECK(message.find("stale TextureHandle") != std::string::npos);
    CHECK_THROWS_AS(device->destroy(a), Error);
    // Using the stale handle in a command is caught too.
    CommandList& cmd = device->beginFrame();
    CHECK(errorOf([&] { cmd.bindStorageImage(0, a); }).find("stale") != std::string::npos);
    device->endFrame();
    CHECK(errorOf([&] { device->desc(TextureHandle{}); }).find("null TextureHandle") != std::string::npos);
    CHECK(errorOf([&] { device->desc(TextureHandle::make(999, 1)); }).find("never created") !=
          std::string::npos);
}

TEST_CASE("null backend: handle types do not mix") {
    static_assert(!std::is_convertible_v<BufferHandle, TextureHandle>);
    static_assert(sizeof(TextureHandle) == 4);
    CHECK_FALSE(TextureHandle{}.valid());
}

TEST_CASE("null backend: allocation record sums by category, current and peak") {
    auto device = nullDevice();
    const AllocationRecord& rec = device->allocations();
    const TextureHandle lpv = device->createTexture(
        {TextureKind::Tex3D, Format::RGBA8Unorm, 32, 32, 32, 1, kTextureStorage, "lpv r", "gi.lpv"});
    const TextureHandle gv = device->createTexture(
        {TextureKind::Tex3D, Format::RGBA16F, 32, 32, 32, 1, kTextureStorage, "gv", "gi.gv"});
    const BufferHandle vb =
        device->createBuffer({1000, kBufferVertex, MemoryAccess::GpuOnly, "verts", "render.mesh"});
    CHECK(rec.bytesIn("gi.lpv") == 32u * 32u * 32u * 4u); // one RGBA8 SH texture = 128 KiB
    CHECK(rec.bytesIn("gi.gv") == 32u * 32u * 32u * 8u);
    CHECK(rec.bytesIn("gi") == 32u * 32u * 32u * 12u);
    CHECK(rec.bytesIn("g") == 0); // prefix matches whole dotted components only
    CHECK(rec.totalBytes() == 32u * 32u * 32u * 12u + 1000u);
    device->destroy(gv);
    CHECK(rec.bytesIn("gi") == 32u * 32u * 32u * 4u);
    CHECK(rec.categories().at("gi.gv").peakBytes == 32u * 32u * 32u * 8u);
    CHECK(rec.categories().at("gi.gv").currentBytes == 0);
    CHECK(rec.peakTotalBytes() == 32u * 32u * 32u * 12u + 1000u);
    REQUIRE(rec.live().size() == 2);
    device->destroy(lpv);
    device->destroy(vb);
    CHECK(rec.totalBytes() == 0);
}

TEST_CASE("null backend: mips and formats are counted") {
    TextureDesc d{TextureKind::Tex2D, Format::RGBA32F, 8, 8, 1, 4, kTextureSampled};
    CHECK(textureBytes(d) == (64 + 16 + 4 + 1) * 16u);
    d.kind = TextureKind::Tex3D;
    d.depthOrLayers = 8;
    d.mipLevels = 2;
    CHECK(textureBytes(d) == (512 + 64) * 16u);
}

TEST_CASE("null backend: a depth-stencil texture is a 2D target only, and a stencil test needs one") {
    const auto device = nullDevice();
    TextureDesc d{TextureKind::Tex2D, Format::D32FS8, 8, 8, 1, 1, kTextureDepthTarget, "classes"};
    const TextureHandle t = device->createTexture(d);
    CHECK(textureBytes(d) == 64 * 8u);
    device->destroy(t);
    d.usage = kTextureDepthTarget | kTextureSampled;
    CHECK(errorOf([&] { device->createTexture(d); }).find("'classes': d32f_s8 is a 2D depth target only") !=
          std::string::npos);

    GraphicsPipelineDesc p;
    static const ShaderBinary vertex{"v.vert", ShaderStage::Vertex, {}, {}};
    p.vertex = &vertex;
    p.stencil.enabled = true;
    p.depthFormat = Format::D32F;
    p.debugName = "class draw";
    CHECK(errorOf([&] { device->createPipeline(p); }) ==
          "pipeline 'class draw': a stencil test needs a depth format with a stencil, not d32f");
    p.depthFormat = Format::D32FS8;
    device->destroy(device->createPipeline(p));
}

TEST_CASE("null backend: frame and pass misuse is reported") {
    auto device = nullDevice();
    CHECK_THROWS_AS(device->endFrame(), Error);
    CommandList& cmd = device->beginFrame();
    CHECK(device->frameIndex() == 1);
    CHECK_THROWS_AS(device->beginFrame(), Error);
    CHECK_THROWS_AS(cmd.draw(3), Error); // outside a render pass
    device->endFrame();
    const BufferHandle b = device->createBuffer({16, kBufferStorage, MemoryAccess::GpuOnly, "b"});
    const uint32_t data[4] = {1, 2, 3, 4};
    device->uploadBuffer(b, 0, data, sizeof(data));
    uint32_t back[4] = {};
    device->readBuffer(b, 0, back, sizeof(back));
    CHECK(back[3] == 4);
    CHECK(errorOf([&] { device->uploadBuffer(b, 8, data, sizeof(data)); }).find("exceeds its size") !=
          std::string::npos);
}

TEST_CASE("null backend: a layered pass is refused without the capability, with mixed targets or depth") {
    for (const bool capable : {false, true}) {
        auto device = nullDevice(capable);
        CHECK(device->caps().vertexShaderLayer == capable);
        const TextureHandle a = device->createTexture(
            {TextureKind::Tex3D, Format::RGBA16F, 4, 4, 4, 1, kTextureColorTarget, "volume a"});
        const TextureHandle b = device->createTexture(
            {TextureKind::Tex3D, Format::RGBA16F, 4, 4, 4, 1, kTextureColorTarget, "volume b"});
        const TextureHandle depth = device->createTexture(
            {TextureKind::Tex2D, Format::D32F, 4, 4, 1, 1, kTextureDepthTarget, "depth"});
        CommandList& cmd = device->beginFrame();
        RenderPassDesc pass;
        pass.colors[0] = {a, 0, 0, LoadOp::Load};
        pass.colors[0].layered = true;
        pass.colorCount = 1;
        pass.debugName = "inject";
        if (!capable) {
            CHECK(errorOf([&] { cmd.beginRenderPass(pass); }).find("Caps::vertexShaderLayer") !=
                  std::string::npos);
        } else {
            pass.colors[1] = {b, 0, 2, LoadOp::Load};
            pass.colorCount = 2;
            CHECK(errorOf([&] { cmd.beginRenderPass(pass); }).find("every color target must be layered") !=
                  std::string::npos);
            pass.colorCount = 1;
            pass.depth = {depth};
            CHECK(errorOf([&] { cmd.beginRenderPass(pass); }).find("no depth target") != std::string::npos);
            pass.depth = {};
            cmd.beginRenderPass(pass);
            cmd.endRenderPass();
        }
        device->endFrame();
        device->destroy(a);
        device->destroy(b);
        device->destroy(depth);
    }
}

TEST_CASE("backend names parse, and unknown ones are rejected") {
    CHECK(parseBackend("gl") == BackendKind::OpenGL);
    CHECK(parseBackend("opengl") == BackendKind::OpenGL);
    CHECK(parseBackend("vulkan") == BackendKind::Vulkan);
    CHECK(parseBackend("auto") == BackendKind::Auto);
    CHECK(parseBackend("null") == BackendKind::Null);
    CHECK_FALSE(parseBackend("d3d9").has_value());
    CHECK(validBackendNames().find("vulkan") != std::string::npos);
    CHECK(backendName(BackendKind::OpenGL) == "gl");
    CHECK(parseGlHeadless("osmesa") == GlHeadless::OSMesa);
    CHECK_FALSE(parseGlHeadless("glx").has_value());
}

TEST_CASE("null backend: simulated timestamps follow the frames-in-flight latency and never block") {
    DeviceConfig config;
    config.backend = BackendKind::Null;
    config.framesInFlight = 2;
    auto device = createDevice(config);
    REQUIRE(device->caps().timestampSource == TimestampSource::Simulated);
    CommandList& cmd = device->beginFrame();
    const uint64_t f1 = device->frameIndex();
    cmd.writeTimestamp(0);
    cmd.dispatch(1);
    cmd.dispatch(1);
    cmd.writeTimestamp(1);
    device->endFrame();
    uint64_t ts[2] = {};
    CHECK_FALSE(device->readTimestamps(f1, ts)); // frame 1 is still "in flight"
    device->beginFrame();                        // frame 2 does not wait for frame 1
    device->endFrame();
    CHECK_FALSE(device->readTimestamps(f1, ts));
    device->beginFrame(); // frame 3 waits for frame 1
    CHECK(device->readTimestamps(f1, ts));
    CHECK(ts[1] - ts[0] == 2000); // two dispatches, 1 us each
    device->endFrame();
    device->beginFrame();
    device->endFrame(); // frame 4 reuses frame 1's slot: results are gone, not wrong
    CHECK_FALSE(device->readTimestamps(f1, ts));
    device->waitIdle();
    CHECK(device->readTimestamps(device->frameIndex(), ts));
}
