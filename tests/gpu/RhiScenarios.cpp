// The shared GPU workloads of the RHI tests (see RhiScenarios.h).
#include "RhiScenarios.h"

#include "TestShaders.h"

#include <glm/vec3.hpp>

#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

namespace lpv::test {
namespace {

struct Vertex {
    float position[3];
    float color[4];
};

} // namespace

MrtImages renderIndexedMrt(rhi::Device& device) {
    using namespace rhi;
    // Triangle B (green, nearer, alpha 0.5) is drawn first so only the depth test makes it win
    // where it overlaps triangle A (red, alpha 1). NDC y = -1 is image row 0 on every backend.
    const Vertex vertices[] = {
        {{-1.0f, -1.0f, 0.5f}, {1, 0, 0, 1}},    {{1.0f, -1.0f, 0.5f}, {1, 0, 0, 1}},
        {{-1.0f, 1.0f, 0.5f}, {1, 0, 0, 1}},     {{0.0f, -1.0f, 0.25f}, {0, 1, 0, 0.5f}},
        {{1.0f, -1.0f, 0.25f}, {0, 1, 0, 0.5f}}, {{1.0f, 0.0f, 0.25f}, {0, 1, 0, 0.5f}},
    };
    const uint16_t indices[] = {3, 4, 5, 0, 1, 2};
    const BufferHandle vb = device.createBuffer(
        {sizeof(vertices), kBufferVertex, MemoryAccess::GpuOnly, "mrt vertices", "test"}, vertices);
    const BufferHandle ib = device.createBuffer(
        {sizeof(indices), kBufferIndex, MemoryAccess::GpuOnly, "mrt indices", "test"}, indices);

    const uint32_t size = 64;
    TextureDesc colorDesc{TextureKind::Tex2D,
                          Format::RGBA8Unorm,
                          size,
                          size,
                          1,
                          1,
                          kTextureColorTarget | kTextureTransfer | kTextureSampled,
                          "mrt color",
                          "test"};
    TextureDesc secondDesc = colorDesc;
    secondDesc.format = Format::RGBA16F;
    secondDesc.debugName = "mrt second";
    TextureDesc depthDesc = colorDesc;
    depthDesc.format = Format::D32F;
    depthDesc.usage = kTextureDepthTarget | kTextureTransfer;
    depthDesc.debugName = "mrt depth";
    const TextureHandle color = device.createTexture(colorDesc);
    const TextureHandle second = device.createTexture(secondDesc);
    const TextureHandle depth = device.createTexture(depthDesc);

    GraphicsPipelineDesc pd;
    pd.vertex = &shaders::mrt_vert;
    pd.fragment = &shaders::mrt_frag;
    pd.vertexBuffers = {{sizeof(Vertex)}};
    pd.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)},
                     {1, VertexFormat::Float4, offsetof(Vertex, color)}};
    pd.depthTest = true;
    pd.depthWrite = true;
    pd.depthCompare = CompareOp::Less;
    pd.colorFormats = {Format::RGBA8Unorm, Format::RGBA16F};
    pd.depthFormat = Format::D32F;
    pd.debugName = "mrt";
    const GraphicsPipelineHandle pipeline = device.createPipeline(pd);

    CommandList& cmd = device.beginFrame();
    RenderPassDesc pass;
    pass.colors[0] = {color, 0, 0, LoadOp::Clear, {kMrtClear.x, kMrtClear.y, kMrtClear.z, kMrtClear.w}};
    pass.colors[1] = {second, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
    pass.colorCount = 2;
    pass.depth = {depth, 0, LoadOp::Clear, 1.0f};
    pass.debugName = "mrt";
    cmd.beginMarker("mrt test");
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline);
    cmd.bindVertexBuffer(0, vb);
    cmd.bindIndexBuffer(ib, IndexType::Uint16);
    cmd.pushUniforms(0, &kMrtTint, sizeof(kMrtTint));
    cmd.drawIndexed(6);
    cmd.endRenderPass();
    cmd.endMarker();
    device.endFrame();
    device.waitIdle();

    MrtImages out{readImage(device, color), readImage(device, second), readImage(device, depth)};
    device.destroy(pipeline);
    device.destroy(color);
    device.destroy(second);
    device.destroy(depth);
    device.destroy(vb);
    device.destroy(ib);
    return out;
}

glm::vec4 expectedVolumeTexel(uint32_t x, uint32_t y, uint32_t z) {
    const glm::vec3 p = glm::vec3(float(x), float(y), float(z)) * glm::vec3(0.1f, 0.2f, 0.05f);
    return {std::sin(p.x) * std::cos(p.y), p.z * 0.5f, float(int(x) + 2 * int(y) - int(z)) / 64.0f,
            1.0f - p.x * p.y};
}

Image fillVolume(rhi::Device& device) {
    using namespace rhi;
    const TextureHandle volume =
        device.createTexture({TextureKind::Tex3D, Format::RGBA16F, kVolumeSize, kVolumeSize, kVolumeSize, 1,
                              kTextureStorage | kTextureSampled | kTextureTransfer, "test volume", "test"});
    const ComputePipelineHandle pipeline =
        device.createPipeline(ComputePipelineDesc{&shaders::fill_volume_comp, "fill volume"});
    const glm::vec4 scale{0.1f, 0.2f, 0.05f, 0.0f};

    CommandList& cmd = device.beginFrame();
    cmd.bindPipeline(pipeline);
    cmd.bindStorageImage(0, volume);
    cmd.pushUniforms(1, &scale, sizeof(scale));
    cmd.dispatch(kVolumeSize / 8, kVolumeSize / 8, kVolumeSize);
    device.endFrame();
    device.waitIdle();

    Image out = readImage(device, volume);
    device.destroy(pipeline);
    device.destroy(volume);
    return out;
}

// A 16x16 RGBA16F target cleared to `clear`, into which `draw` adds the constant fragment
// shader's kBlendColor through `vertex`'s primitives; read back.
Image drawAdditive(rhi::Device& device, const rhi::ShaderBinary& vertex, rhi::PrimitiveTopology topology,
                   glm::vec4 clear, const char* name, const std::function<void(rhi::CommandList&)>& draw) {
    using namespace rhi;
    const TextureHandle target = device.createTexture({TextureKind::Tex2D, Format::RGBA16F, 16, 16, 1, 1,
                                                       kTextureColorTarget | kTextureTransfer, name, "test"});
    GraphicsPipelineDesc pd;
    pd.vertex = &vertex;
    pd.fragment = &shaders::constant_frag;
    pd.topology = topology;
    pd.colorFormats = {Format::RGBA16F};
    pd.blend = {BlendState::additive()};
    pd.debugName = name;
    const GraphicsPipelineHandle pipeline = device.createPipeline(pd);

    CommandList& cmd = device.beginFrame();
    RenderPassDesc pass;
    pass.colors[0] = {target, 0, 0, LoadOp::Clear, {clear.x, clear.y, clear.z, clear.w}};
    pass.colorCount = 1;
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline);
    cmd.pushUniforms(0, &kBlendColor, sizeof(kBlendColor));
    draw(cmd);
    cmd.endRenderPass();
    device.endFrame();
    device.waitIdle();

    Image out = readImage(device, target);
    device.destroy(pipeline);
    device.destroy(target);
    return out;
}

Image additiveBlend(rhi::Device& device) {
    return drawAdditive(device, shaders::fullscreen_vert, rhi::PrimitiveTopology::TriangleList, kBlendClear,
                        "additive", [](rhi::CommandList& cmd) {
                            cmd.draw(3);
                            cmd.draw(3);
                        });
}

Image drawPoints(rhi::Device& device) {
    return drawAdditive(device, shaders::points_vert, rhi::PrimitiveTopology::PointList, glm::vec4(0.0f),
                        "points", [](rhi::CommandList& cmd) { cmd.draw(kPointCount, 1, kFirstPoint); });
}

glm::vec4 expectedPointTexel(uint32_t x, uint32_t y) {
    float hits = 0.0f;
    for (uint32_t i = kFirstPoint; i < kFirstPoint + kPointCount; ++i)
        if (i % 3 != 0 && i % 16 == x && i / 16 % 16 == y) hits += 1.0f;
    return hits * kBlendColor;
}

MultiDrawResult multiDrawQuads(rhi::Device& device) {
    using namespace rhi;
    const TextureHandle target =
        device.createTexture({TextureKind::Tex2D, Format::RGBA16F, 16, 4, 1, 1,
                              kTextureColorTarget | kTextureTransfer, "multi-draw", "test"});
    std::vector<float> positions;
    std::vector<uint32_t> indices;
    for (uint32_t q = 0; q < 4; ++q) {
        const float x0 = -1.0f + 0.5f * float(q), x1 = x0 + 0.5f;
        const uint32_t v = uint32_t(positions.size() / 2);
        positions.insert(positions.end(), {x0, -1.0f, x1, -1.0f, x1, 1.0f, x0, 1.0f});
        indices.insert(indices.end(), {v, v + 1, v + 2, v, v + 2, v + 3});
    }
    const BufferHandle vertices = device.createBuffer(
        {positions.size() * sizeof(float), kBufferVertex, MemoryAccess::GpuOnly, "quads", "test"},
        positions.data());
    const BufferHandle values = device.createBuffer(
        {sizeof(kMultiDrawValues), kBufferVertex, MemoryAccess::GpuOnly, "values", "test"}, kMultiDrawValues);
    const BufferHandle index = device.createBuffer(
        {indices.size() * sizeof(uint32_t), kBufferIndex, MemoryAccess::GpuOnly, "quad indices", "test"},
        indices.data());
    const BufferHandle commands =
        device.createBuffer({sizeof(DrawIndexedIndirectCommand) * 3, kBufferIndirect, MemoryAccess::HostWrite,
                             "commands", "test"});
    auto* c = static_cast<DrawIndexedIndirectCommand*>(device.mapped(commands));
    for (uint32_t k = 0; k < 3; ++k)
        c[k] = {6, 1, 6 * kMultiDraws[k][0], 0, kMultiDraws[k][1]};
    GraphicsPipelineDesc pd;
    pd.vertex = &shaders::multi_draw_vert;
    pd.fragment = &shaders::multi_draw_frag;
    pd.vertexBuffers = {{2 * sizeof(float)}, {sizeof(uint32_t), true}};
    pd.attributes = {{0, VertexFormat::Float2, 0, 0}, {6, VertexFormat::UInt1, 0, 1}};
    pd.colorFormats = {Format::RGBA16F};
    pd.debugName = "multi-draw";
    const GraphicsPipelineHandle pipeline = device.createPipeline(pd);

    CommandList& cmd = device.beginFrame();
    RenderPassDesc pass;
    pass.colors[0] = {target, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
    pass.colorCount = 1;
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline);
    cmd.bindVertexBuffer(0, vertices);
    cmd.bindVertexBuffer(1, values);
    cmd.bindIndexBuffer(index, IndexType::Uint32);
    cmd.drawIndexedIndirect(commands, 0, 3);
    cmd.endRenderPass();
    device.endFrame();
    device.waitIdle();

    MultiDrawResult out{readImage(device, target), device.frameCounters()};
    device.destroy(pipeline);
    for (BufferHandle b : {vertices, values, index, commands})
        device.destroy(b);
    device.destroy(target);
    return out;
}

Image drawStencilFields(rhi::Device& device) {
    using namespace rhi;
    const TextureHandle target =
        device.createTexture({TextureKind::Tex2D, Format::RGBA16F, 16, 16, 1, 1,
                              kTextureColorTarget | kTextureTransfer, "stencil color", "test"});
    const TextureHandle stencil = device.createTexture(
        {TextureKind::Tex2D, Format::D32FS8, 16, 16, 1, 1, kTextureDepthTarget, "stencil fields", "test"});
    GraphicsPipelineDesc pd;
    pd.vertex = &shaders::fullscreen_vert;
    pd.fragment = &shaders::stencil_export_frag;
    pd.colorFormats = {Format::RGBA16F};
    pd.blend = {BlendState::additive()};
    pd.depthFormat = Format::D32FS8;
    pd.stencil = {true, CompareOp::Always, 0, 0xff, 0xff, StencilOp::Replace};
    pd.debugName = "stencil export";
    const GraphicsPipelineHandle exportPipeline = device.createPipeline(pd);
    pd.fragment = &shaders::constant_frag;
    GraphicsPipelineHandle tests[3];
    for (int i = 0; i < 3; ++i) {
        pd.stencil = {true, CompareOp::Equal, kStencilRefs[i], kStencilMasks[i], 0, StencilOp::Keep};
        pd.debugName = "stencil test";
        tests[i] = device.createPipeline(pd);
    }

    CommandList& cmd = device.beginFrame();
    RenderPassDesc pass;
    pass.colors[0] = {target, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
    pass.colorCount = 1;
    pass.depth = {stencil, 0, LoadOp::Clear, 1.0f, kStencilClear};
    pass.debugName = "stencil fields";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(exportPipeline);
    cmd.draw(3);
    for (int i = 0; i < 3; ++i) {
        cmd.bindPipeline(tests[i]);
        cmd.pushUniforms(0, &kStencilColors[i], sizeof(glm::vec4));
        cmd.draw(3);
    }
    cmd.endRenderPass();
    device.endFrame();
    device.waitIdle();

    Image out = readImage(device, target);
    for (const GraphicsPipelineHandle p : tests)
        device.destroy(p);
    device.destroy(exportPipeline);
    device.destroy(stencil);
    device.destroy(target);
    return out;
}

glm::vec4 expectedStencilTexel(uint32_t x, uint32_t y) {
    const uint32_t s = x >= 12 ? kStencilClear : (x & 3) | ((y & 3) << 4);
    glm::vec4 sum(0.0f);
    for (int i = 0; i < 3; ++i)
        if ((s & kStencilMasks[i]) == kStencilRefs[i]) sum += kStencilColors[i];
    return sum;
}

Image drawLayeredPoints(rhi::Device& device) {
    using namespace rhi;
    const TextureHandle volume = device.createTexture(
        {TextureKind::Tex3D, Format::RGBA16F, kLayeredSize, kLayeredSize, kLayeredSize, 1,
         kTextureColorTarget | kTextureSampled | kTextureTransfer, "layered volume", "test"});
    GraphicsPipelineDesc pd;
    pd.vertex = &shaders::layered_points_vert;
    pd.fragment = &shaders::constant_frag;
    pd.topology = PrimitiveTopology::PointList;
    pd.colorFormats = {Format::RGBA16F};
    pd.blend = {BlendState::additive()};
    pd.debugName = "layered points";
    const GraphicsPipelineHandle points = device.createPipeline(pd);

    CommandList& cmd = device.beginFrame();
    cmd.clearTexture(volume, {0, 0, 0, 0});
    RenderPassDesc pass;
    pass.colors[0] = {volume, 0, 0, LoadOp::Load};
    pass.colors[0].layered = true;
    pass.colorCount = 1;
    pass.debugName = "layered points";
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(points);
    cmd.pushUniforms(0, &kBlendColor, sizeof(kBlendColor));
    cmd.draw(kLayeredPointCount);
    cmd.endRenderPass();
    device.endFrame();
    device.waitIdle();

    Image out = readImage(device, volume);
    device.destroy(points);
    device.destroy(volume);
    return out;
}

glm::vec4 expectedLayeredTexel(uint32_t x, uint32_t y, uint32_t z) {
    float hits = 0.0f;
    for (uint32_t i = 0; i < kLayeredPointCount; ++i)
        if (i % 5 != 0 && i % 4 == x && i / 4 % 4 == y && i / 16 % 4 == z) hits += 1.0f;
    return hits * kBlendColor;
}

InjectionResult injectIntoSlice(rhi::Device& device) {
    using namespace rhi;
    const TextureHandle volume = device.createTexture(
        {TextureKind::Tex3D, Format::RGBA16F, kInjectSize, kInjectSize, kInjectSize, 1,
         kTextureColorTarget | kTextureSampled | kTextureTransfer, "injection volume", "test"});
    const uint32_t texels = kInjectSize * kInjectSize * kInjectSize;
    const BufferHandle result =
        device.createBuffer({texels * sizeof(glm::vec4), kBufferStorage | kBufferTransfer,
                             MemoryAccess::GpuOnly, "sampled reads", "test"});
    const SamplerHandle nearest = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});

    GraphicsPipelineDesc pd;
    pd.vertex = &shaders::fullscreen_vert;
    pd.fragment = &shaders::constant_frag;
    pd.colorFormats = {Format::RGBA16F};
    pd.blend = {BlendState::additive()};
    pd.debugName = "inject";
    const GraphicsPipelineHandle inject = device.createPipeline(pd);
    const ComputePipelineHandle sample =
        device.createPipeline(ComputePipelineDesc{&shaders::sample_volume_comp, "sample volume"});

    CommandList& cmd = device.beginFrame();
    cmd.clearTexture(volume, {0, 0, 0, 0});
    RenderPassDesc pass;
    pass.colors[0] = {volume, 0, kInjectSlice, LoadOp::Load};
    pass.colorCount = 1;
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(inject);
    cmd.pushUniforms(0, &kBlendColor, sizeof(kBlendColor));
    cmd.draw(3);
    cmd.draw(3);
    cmd.endRenderPass();
    cmd.bindPipeline(sample);
    cmd.bindTexture(0, volume, nearest);
    cmd.bindStorageBuffer(1, result);
    cmd.dispatch((texels + 63) / 64);
    device.endFrame();
    device.waitIdle();

    InjectionResult out;
    out.readback = readImage(device, volume);
    out.sampledReads.resize(texels);
    device.readBuffer(result, 0, out.sampledReads.data(), texels * sizeof(glm::vec4));
    device.destroy(inject);
    device.destroy(sample);
    device.destroy(nearest);
    device.destroy(result);
    device.destroy(volume);
    return out;
}

} // namespace lpv::test
