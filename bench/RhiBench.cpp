// RHI benchmark: per backend, the cost of device creation, pipeline creation, a 32^3 compute
// dispatch and a 1280x720 two-target draw of 100k indexed triangles. Each figure is the median of
// several runs. GPU figures come from the device's timestamps and say which timing source that
// was; the wall figure (submit to idle, CPU clock) is printed beside them.
//
//   lpv_rhi_bench [--backends=vulkan,gl-egl,gl-osmesa] [--runs=N]
#include "BenchBackends.h"
#include "BenchCommandLine.h"
#include "BenchShaders.h"

#include "platforms/Clock.h"
#include "platforms/Log.h"
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::rhi;
using namespace lpv::bench;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : (v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]));
}

double msSince(uint64_t t0) {
    return double(platforms::nowNanoseconds() - t0) / 1e6;
}

struct Vertex {
    float position[3];
    float color[4];
};

// A grid of `triangles` small triangles covering the screen, with depth varying so the depth
// test does real work.
void makeMesh(uint32_t triangles, std::vector<Vertex>& vertices, std::vector<uint32_t>& indices) {
    const uint32_t quads = triangles / 2;
    uint32_t cols = 1;
    while (cols * cols < quads)
        ++cols;
    const uint32_t rows = (quads + cols - 1) / cols;
    for (uint32_t y = 0; y <= rows; ++y)
        for (uint32_t x = 0; x <= cols; ++x) {
            const float fx = float(x) / float(cols), fy = float(y) / float(rows);
            vertices.push_back({{fx * 2 - 1, fy * 2 - 1, 0.25f + 0.5f * fx * fy}, {fx, fy, 1 - fx, 1}});
        }
    for (uint32_t q = 0; q < quads; ++q) {
        const uint32_t x = q % cols, y = q / cols;
        const uint32_t i0 = y * (cols + 1) + x, i1 = i0 + 1, i2 = i0 + cols + 1, i3 = i2 + 1;
        indices.insert(indices.end(), {i0, i1, i2, i1, i3, i2});
    }
}

// Runs `record` in a frame `runs` times; returns {median GPU ms from timestamps 0..1, median wall ms}.
std::pair<double, double> timeFrames(Device& device, int runs,
                                     const std::function<void(CommandList&)>& record) {
    std::vector<double> gpu, wall;
    for (int i = 0; i < runs + 1; ++i) { // first run warms caches and is dropped
        const uint64_t t0 = platforms::nowNanoseconds();
        CommandList& cmd = device.beginFrame();
        const uint64_t frame = device.frameIndex();
        cmd.writeTimestamp(0);
        record(cmd);
        cmd.writeTimestamp(1);
        device.endFrame();
        device.waitIdle();
        const double w = msSince(t0);
        uint64_t ts[2] = {};
        if (i > 0) {
            wall.push_back(w);
            if (device.readTimestamps(frame, ts)) gpu.push_back(double(ts[1] - ts[0]) / 1e6);
        }
    }
    return {gpu.empty() ? -1.0 : median(gpu), median(wall)};
}

void benchBackend(const BenchBackend& b, int runs) {
    std::vector<double> create;
    for (int i = 0; i < runs; ++i) {
        const uint64_t t0 = platforms::nowNanoseconds();
        auto d = makeDevice(b);
        create.push_back(msSince(t0));
    }
    auto device = makeDevice(b);
    const Caps& caps = device->caps();

    GraphicsPipelineDesc pd;
    pd.vertex = &bench::shaders::mrt_vert;
    pd.fragment = &bench::shaders::mrt_frag;
    pd.vertexBuffers = {{sizeof(Vertex)}};
    pd.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)},
                     {1, VertexFormat::Float4, offsetof(Vertex, color)}};
    pd.depthTest = pd.depthWrite = true;
    pd.colorFormats = {Format::RGBA8Unorm, Format::RGBA16F};
    pd.depthFormat = Format::D32F;
    pd.debugName = "bench mrt";
    std::vector<double> graphicsCreate, computeCreate;
    for (int i = 0; i < runs; ++i) {
        uint64_t t0 = platforms::nowNanoseconds();
        const GraphicsPipelineHandle g = device->createPipeline(pd);
        graphicsCreate.push_back(msSince(t0));
        t0 = platforms::nowNanoseconds();
        const ComputePipelineHandle c =
            device->createPipeline(ComputePipelineDesc{&bench::shaders::fill_volume_comp, "bench fill"});
        computeCreate.push_back(msSince(t0));
        device->destroy(g);
        device->destroy(c);
    }
    const GraphicsPipelineHandle mrt = device->createPipeline(pd);
    const ComputePipelineHandle fill =
        device->createPipeline(ComputePipelineDesc{&bench::shaders::fill_volume_comp, "bench fill"});

    const TextureHandle volume = device->createTexture(
        {TextureKind::Tex3D, Format::RGBA16F, 32, 32, 32, 1, kTextureStorage, "bench volume", "bench"});
    const float scale[4] = {0.1f, 0.2f, 0.05f, 0.0f};
    const auto [dispatchGpu, dispatchWall] = timeFrames(*device, runs * 3, [&](CommandList& cmd) {
        cmd.bindPipeline(fill);
        cmd.bindStorageImage(0, volume);
        cmd.pushUniforms(1, scale, sizeof(scale));
        cmd.dispatch(4, 4, 32);
    });

    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    makeMesh(100000, vertices, indices);
    const BufferHandle vb = device->createBuffer(
        {vertices.size() * sizeof(Vertex), kBufferVertex, MemoryAccess::GpuOnly, "bench vb", "bench"},
        vertices.data());
    const BufferHandle ib = device->createBuffer(
        {indices.size() * sizeof(uint32_t), kBufferIndex, MemoryAccess::GpuOnly, "bench ib", "bench"},
        indices.data());
    const TextureHandle c0 = device->createTexture(
        {TextureKind::Tex2D, Format::RGBA8Unorm, 1280, 720, 1, 1, kTextureColorTarget, "bench c0", "bench"});
    const TextureHandle c1 = device->createTexture(
        {TextureKind::Tex2D, Format::RGBA16F, 1280, 720, 1, 1, kTextureColorTarget, "bench c1", "bench"});
    const TextureHandle depth = device->createTexture(
        {TextureKind::Tex2D, Format::D32F, 1280, 720, 1, 1, kTextureDepthTarget, "bench depth", "bench"});
    const float tint[4] = {0.25f, 0.5f, 0.75f, 1.0f};
    const auto [drawGpu, drawWall] = timeFrames(*device, runs, [&](CommandList& cmd) {
        RenderPassDesc pass;
        pass.colors[0] = {c0, 0, 0, LoadOp::Clear, {0, 0, 0, 1}};
        pass.colors[1] = {c1, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
        pass.colorCount = 2;
        pass.depth = {depth, 0, LoadOp::Clear, 1.0f};
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(mrt);
        cmd.bindVertexBuffer(0, vb);
        cmd.bindIndexBuffer(ib, IndexType::Uint32);
        cmd.pushUniforms(0, tint, sizeof(tint));
        cmd.drawIndexed(uint32_t(indices.size()));
        cmd.endRenderPass();
    });

    const std::string source(timestampSourceName(caps.timestampSource));
    std::printf("| %-9s | %8.1f | %8.2f | %8.2f | %8.3f | %8.3f | %8.2f | %8.2f | %-16s |\n", b.name.c_str(),
                median(create), median(graphicsCreate), median(computeCreate), dispatchGpu, dispatchWall,
                drawGpu, drawWall, source.c_str());
    std::fflush(stdout);
    for (TextureHandle t : {volume, c0, c1, depth})
        device->destroy(t);
    for (BufferHandle h : {vb, ib})
        device->destroy(h);
    device->destroy(mrt);
    device->destroy(fill);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "RHI benchmark: device and pipeline creation, a compute dispatch and an MRT draw per backend"};
    std::vector<BenchBackend> backends;
    addBackendsOption(app, backends);
    int runs = 5;
    app.add_option("--runs", runs, "Runs per figure (the median is printed)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    if (const std::optional<int> exit = parseCommandLine(app, argc, argv)) return *exit;
    std::printf("RHI benchmark, median of %d runs (ms). GPU columns: as the row's timing source measures "
                "them (gpu-timestamp: the device's timestamps; cpu-after-finish: CPU time around a finish); "
                "wall: submit to idle.\n",
                runs);
    std::printf("| backend   | device   | gfx pipe | cmp pipe | 32^3 gpu | 32^3 wall| 100k gpu | 100k wall| "
                "timing source    |\n");
    std::printf("|-----------|----------|----------|----------|----------|----------|----------|----------|--"
                "----------------|\n");
    int failures = 0;
    for (const auto& b : backends) {
        try {
            benchBackend(b, runs);
        } catch (const Error& e) {
            std::printf("| %-9s | unavailable: %s\n", b.name.c_str(), e.what());
            ++failures;
        }
    }
    return failures ? 1 : 0;
}
