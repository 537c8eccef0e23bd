// GI benchmark, two parts, every backend in one run (compare ratios, not absolute times: this
// machine is noisy):
//  1. Propagation kernels: the shipped kernel, with bounded partial sums (one cascade) and with a
//     shell (several cascades, gi::partialSumShell), against the straightforward 5-face gather kept
//     here as the baseline, 32^3 x 8 iterations, RGBA16F, same injected VPLs; median GPU time of
//     each, the speedups as the medians of the per-run ratios (all three run in the same frame),
//     and the largest difference between their results.
//  1b. Analytic lights: the gi/lights pass alone (gi/PointLightInjection.h) for 128 and 1024 point
//     lights of the lights hall, 32^3, RGBA16F; median GPU time.
//  2. Frames: the Cornell box and the atrium at 1280x720 with GI on (3 cascades of 32^3, 8
//     iterations, 2 bounces, occlusion, glossy) along a scripted camera, the sun moving; per-pass median GPU
//     times from the frame profiler, GI share of the frame, memory by category, and the predicted Xbox 360 /
//     PS3 GI time of the frame's work and of the CryEngine 3 console setup (32^3, 128^2 RSM, 6 iterations,
//     RGBA8).
//
//   lpv_bench [--backends=vulkan,gl-egl,gl-osmesa] [--runs=N] [--kernel-runs=N] [--frames=N]
//             [--scenes=cornell,atrium] [--parts=propagation,lights,frames,profiler,console] [--out=DIR]
//             [--config=FILE ...] [--set key=value ...]   (lpv_bench --help says what each does)
#include "BenchBackends.h"
#include "BenchCommandLine.h"
#include "BenchShaders.h"

#include "engine/Screenshot.h"
#include "engine/config/Config.h"
#include "engine/profiler/CostModel.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/profiler/ProfileReport.h"
#include "engine/render/CameraPath.h"
#include "engine/render/Renderer.h"
#include "engine/render/SpecularAlbedoTexture.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/GeometryVolume.h"
#include "gi/GiBudget.h"
#include "gi/GiScheduler.h"
#include "gi/GiWork.h"
#include "gi/GlossyReflections.h"
#include "gi/LightPropagationVolume.h"
#include "gi/LpvInjection.h"
#include "gi/LpvPropagation.h"
#include "gi/LpvSettings.h"
#include "gi/LpvVolumes.h"
#include "gi/PointLightInjection.h"
#include "gi/ReflectiveShadowMap.h"
#include "gi/SpotLightRsms.h"
#include "gi/adapter/EngineFrame.h"
#include "gi/adapter/LpvConfig.h"
#include "platforms/Clock.h"
#include "platforms/Platform.h"
#include "rhi/Device.h"
#include "rhi/Error.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

using namespace lpv;
using namespace lpv::bench;

namespace {

double median(std::vector<double> v) {
    if (v.empty()) return -1.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// The q-quantile (0..1) by nearest rank.
double quantile(std::vector<double> v, double q) {
    if (v.empty()) return -1.0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5))];
}

struct GpuVpl {
    glm::vec4 position, normal, flux;
};

std::vector<float> readVolume(rhi::Device& device, rhi::TextureHandle t) {
    const rhi::TextureDesc& d = device.desc(t);
    std::vector<uint16_t> half(size_t(d.width) * d.height * d.depthOrLayers * 4);
    device.readTexture(t, 0, half.data(), half.size() * 2);
    std::vector<float> out(half.size());
    for (size_t i = 0; i < half.size(); ++i)
        out[i] = glm::unpackHalf1x16(half[i]);
    return out;
}

void benchPropagation(const BenchBackend& b, int runs) {
    using namespace rhi;
    auto device = makeDevice(b);
    gi::LpvSettings s;
    s.gridSize = 32;
    s.iterations = 8;
    s.shFormat = gi::ShFormat::Rgba16f;
    const gi::VolumeGrid grid{{0, 0, 0}, 0.25f, 32};
    std::vector<GpuVpl> vpls;
    uint32_t state = 7;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24);
    };
    for (int i = 0; i < 4096; ++i) {
        const glm::vec3 n =
            glm::normalize(glm::vec3(next() - 0.5f, next(), next() - 0.5f) + glm::vec3(0, 0.1f, 0));
        vpls.push_back({glm::vec4(next() * 8, next() * 8, next() * 8, 1), glm::vec4(n, 0),
                        glm::vec4(next(), next(), next(), 0) * 0.01f});
    }
    const BufferHandle vplBuffer = device->createBuffer(
        {vpls.size() * sizeof(GpuVpl), kBufferStorage, MemoryAccess::GpuOnly, "bench vpls", "bench"},
        vpls.data());
    s.cascades = 1;
    gi::LpvVolumes volumes(*device, s); // bounded partial sums
    gi::LpvInjection injection(*device, s);
    gi::LpvPropagation propagation(*device, s);
    gi::LpvSettings cascaded = s;
    cascaded.cascades = 3;
    gi::LpvVolumes shellVolumes(*device, cascaded); // with the shell (seeded with nothing here)
    gi::LpvPropagation shellPropagation(*device, cascaded);
    // Baseline volumes: per channel a ping, a pong and an accumulation, RGBA16F.
    std::array<TextureHandle, 3> start{}, ping{}, pong{}, acc{};
    for (int c = 0; c < 3; ++c) {
        const auto vol = [&](const char* name) {
            return device->createTexture({TextureKind::Tex3D, Format::RGBA16F, 32, 32, 32, 1,
                                          kTextureStorage | kTextureSampled | kTextureTransfer, name,
                                          "bench"});
        };
        start[size_t(c)] = vol("baseline start");
        ping[size_t(c)] = vol("baseline ping");
        pong[size_t(c)] = vol("baseline pong");
        acc[size_t(c)] = vol("baseline acc");
    }
    const ComputePipelineHandle baseline = device->createPipeline(
        ComputePipelineDesc{&bench::shaders::propagate_baseline_comp, "baseline propagate"});
    const ComputePipelineHandle accumulate = device->createPipeline(
        ComputePipelineDesc{&bench::shaders::accumulate_baseline_comp, "baseline accumulate"});
    const glm::ivec4 params(32, 0, 0, 0);

    std::vector<double> shipped, shelled, straightforward, ratios, shellRatios;
    for (int run = 0; run < runs + 1; ++run) {
        CommandList& cmd = device->beginFrame();
        const uint64_t frame = device->frameIndex();
        injection.record(cmd, volumes, vplBuffer, uint32_t(vpls.size()), grid, {0, -1, 0}, 1.0f);
        injection.record(cmd, shellVolumes, vplBuffer, uint32_t(vpls.size()), grid, {0, -1, 0}, 1.0f);
        // The baseline reads images: it starts from copies of the injected volume.
        for (int c = 0; c < 3; ++c) {
            cmd.copyTexture(volumes.injected()[size_t(c)], acc[size_t(c)]);
            cmd.copyTexture(volumes.injected()[size_t(c)], start[size_t(c)]);
        }
        cmd.writeTimestamp(0);
        propagation.record(cmd, volumes, s.iterations);
        cmd.writeTimestamp(1);
        shellPropagation.record(cmd, shellVolumes, s.iterations);
        cmd.writeTimestamp(2);
        const std::array<TextureHandle, 3>* src = &start;
        for (uint32_t i = 0; i < s.iterations; ++i) {
            const std::array<TextureHandle, 3>* dst = (i % 2 == 0) ? &ping : &pong;
            for (int c = 0; c < 3; ++c) {
                cmd.bindPipeline(baseline);
                cmd.pushUniforms(0, &params, sizeof(params));
                cmd.bindStorageImage(1, (*src)[size_t(c)]);
                cmd.bindStorageImage(2, (*dst)[size_t(c)]);
                cmd.dispatch(8, 8, 8);
                cmd.bindPipeline(accumulate);
                cmd.pushUniforms(0, &params, sizeof(params));
                cmd.bindStorageImage(1, (*dst)[size_t(c)]);
                cmd.bindStorageImage(2, acc[size_t(c)]);
                cmd.dispatch(8, 8, 8);
            }
            src = dst;
        }
        cmd.writeTimestamp(3);
        device->endFrame();
        device->waitIdle();
        uint64_t ts[4] = {};
        if (run > 0 && device->readTimestamps(frame, ts)) {
            shipped.push_back(double(ts[1] - ts[0]) / 1e6);
            shelled.push_back(double(ts[2] - ts[1]) / 1e6);
            straightforward.push_back(double(ts[3] - ts[2]) / 1e6);
            ratios.push_back(straightforward.back() / shipped.back());
            shellRatios.push_back(straightforward.back() / shelled.back());
        }
    }
    float worst = 0, peak = 0;
    for (int c = 0; c < 3; ++c) {
        const std::vector<float> a = readVolume(*device, volumes.accumulated()[size_t(c)]);
        const std::vector<float> sh = readVolume(*device, shellVolumes.accumulated()[size_t(c)]);
        const std::vector<float> bsl = readVolume(*device, acc[size_t(c)]);
        for (size_t i = 0; i < a.size(); ++i) {
            worst = std::max({worst, std::fabs(a[i] - bsl[i]), std::fabs(sh[i] - bsl[i])});
            peak = std::max(peak, std::fabs(bsl[i]));
        }
    }
    // The kernels run in the same frame, so the per-run ratio cancels most of the machine's noise;
    // the quartiles say how much is left.
    std::printf("| %-9s | %10.2f | %8.2f | %11.2f | %6.2fx | %5.2f-%5.2fx | %6.2fx | %5.2f-%5.2fx | %12.2e | "
                "%-16s |\n",
                b.name.c_str(), median(shipped), median(shelled), median(straightforward), median(ratios),
                quantile(ratios, 0.25), quantile(ratios, 0.75), median(shellRatios),
                quantile(shellRatios, 0.25), quantile(shellRatios, 0.75), peak > 0 ? worst / peak : 0.0,
                std::string(rhi::timestampSourceName(device->caps().timestampSource)).c_str());
    std::fflush(stdout);
    device->waitIdle();
    for (const auto* set : {&start, &ping, &pong, &acc})
        for (TextureHandle t : *set)
            device->destroy(t);
    device->destroy(baseline);
    device->destroy(accumulate);
    device->destroy(vplBuffer);
}

// The analytic-lights pass alone: the first `count` point lights of the lights hall added to a
// 32^3 RGBA16F volume that spans the hall, timed by GPU timestamps around the pass.
void benchAnalyticLights(const BenchBackend& b, int runs) {
    auto device = makeDevice(b);
    gi::LpvSettings s;
    s.gridSize = 32;
    s.shFormat = gi::ShFormat::Rgba16f;
    const gi::VolumeGrid grid{{-4.0f, -2.75f, -4.0f}, 0.25f, 32};
    gi::LpvVolumes volumes(*device, s);
    gi::PointLightInjection injection(*device, s);
    std::printf("| %-9s |", b.name.c_str());
    for (const uint32_t count : {128u, 1024u}) {
        std::vector<engine::Light> lights;
        for (const engine::Light& l : engine::buildLightHall(count).lights)
            if (l.type == engine::LightType::Point) lights.push_back(l);
        std::vector<double> ms;
        uint32_t added = 0;
        for (int run = 0; run < runs + 1; ++run) {
            rhi::CommandList& cmd = device->beginFrame();
            const uint64_t frame = device->frameIndex();
            for (rhi::TextureHandle t : volumes.accumulated())
                cmd.clearTexture(t, {0, 0, 0, 0});
            cmd.writeTimestamp(0);
            added = injection.record(cmd, lights, volumes, grid, 1.0f);
            cmd.writeTimestamp(1);
            device->endFrame();
            device->waitIdle();
            uint64_t ts[2] = {};
            if (run > 0 && device->readTimestamps(frame, ts)) ms.push_back(double(ts[1] - ts[0]) / 1e6);
        }
        // Every light of the hall lies in the volume; a cell says so when some were not added.
        if (added == lights.size())
            std::printf(" %10.2f |", median(ms));
        else
            std::printf(" %.2f (%u of %zu added) |", median(ms), added, lights.size());
    }
    std::printf(" %-16s |\n", std::string(rhi::timestampSourceName(device->caps().timestampSource)).c_str());
    std::fflush(stdout);
}

// What the frames part runs with besides the scene: --config's files, then --set's assignments.
struct FrameOverrides {
    std::vector<std::string> files;
    std::vector<std::string> assignments;
};

// The frames part's settings for a scene: the benchmark's own (named as lpv_bench's in errors),
// then --config's files in order (a game's config, or gi/presets/console.toml), then --set's.
engine::Config frameSettings(const std::string& sceneName, const FrameOverrides& overrides) {
    engine::Config config;
    for (const char* own : {"gi.enabled=true", "gi.grid_size=32", "gi.iterations=8", "gi.bounces=2"})
        config.applyOverride(own, "lpv_bench's frames part");
    config.applyOverride(sceneName == "atrium" ? "gi.cell_size=1.0" : "gi.cell_size=0.2",
                         "lpv_bench's frames part");
    // The atrium's frames carry the fog row (gi.fog: half resolution, default steps).
    if (sceneName == "atrium") config.applyOverride("fog.enabled=true", "lpv_bench's frames part");
    for (const std::string& file : overrides.files)
        config.loadFile(file);
    for (const std::string& o : overrides.assignments)
        config.applyOverride(o);
    return config;
}

const engine::SettingDecl& settingNamed(const char* name) {
    const engine::SettingDecl* decl = engine::SettingRegistry::global().find(name);
    if (!decl) throw std::logic_error(std::string("lpv_bench: no setting ") + name);
    return *decl;
}

// Settings the frames part cannot time as given, from whichever file or --set gave them: the empty
// string when there is none. gi.enabled=false gave a black "GI on" screenshot under a GI heading;
// gi.debug_view=indirect is the game's shortcut that moves render.debug_view, which the
// benchmark's renderer does not follow.
std::string framesRefusal(const engine::Config& config) {
    const engine::SettingDecl& enabled = settingNamed("gi.enabled");
    if (!std::get<bool>(config.value(enabled)))
        return config.origin(enabled) +
               ": gi.enabled = false: the frames part runs every frame with GI on, and once more with it off "
               "for the screenshot beside it; leave gi.enabled out";
    const engine::SettingDecl& view = settingNamed("gi.debug_view");
    if (std::get<std::string>(config.value(view)) == "indirect")
        return config.origin(view) +
               ": gi.debug_view = indirect: in lpv_bench set render.debug_view=indirect for the indirect "
               "light alone (the game's gi.debug_view=indirect sets it for you)";
    return {};
}

// The settings a frames table was timed with, for its heading.
std::string describe(const engine::Config& config) {
    const gi::LpvSettings s = gi::readLpvSettings(config);
    const std::string& resolution = std::get<std::string>(config.value(settingNamed("gi.resolution")));
    std::string out = std::to_string(s.cascades) + " x " + std::to_string(s.gridSize) + "^3, " +
                      std::to_string(s.iterations) + " iterations, " + std::to_string(s.bounces) +
                      (s.bounces == 1 ? " bounce, " : " bounces, ") + resolution + " resolution, " +
                      std::string(gi::shFormatName(s.shFormat)) + ", RSM " + std::to_string(s.rsmSize) + "^2";
    if (s.coarseUpdateInterval > 1)
        out += ", coarse cascades every " + std::to_string(s.coarseUpdateInterval) + " frames";
    return out;
}

// `outDir` (may be empty): where the run's profiler outputs (trace.json, frames.svg, summaries) and
// its last frame with GI on and with GI off go, as <scene>-<backend>-*.
void benchFrames(const BenchBackend& b, const std::string& sceneName, int frames, const std::string& outDir,
                 const FrameOverrides& overrides) {
    auto device = makeDevice(b);
    engine::Config config = frameSettings(sceneName, overrides);
    const engine::Scene scene = engine::buildBuiltinScene(sceneName);
    const uint32_t w = 1280, h = 720;
    engine::Renderer renderer(*device, w, h);
    renderer.setScene(scene);
    const auto pc = platforms::loadPlatformProfile("pc");
    engine::FrameProfiler profiler(*device, pc);
    gi::LightPropagationVolume lpv(*device, pc);
    const engine::Camera start = *scene.camera;
    // The atrium flies a quarter of its path; the Cornell box, open only toward +z, orbits 10
    // degrees to either side of its front, looking in (a quarter orbit from the front, as before,
    // ended outside the green wall, so most frames showed its outer face).
    const auto cameraAt = [&](float t) {
        return sceneName == "atrium" ? engine::cameraOnPath("flythrough", scene.bounds, start, t * 0.25f)
                                     : engine::cameraOnPath("orbit", scene.bounds, start, (t - 0.5f) / 18.0f);
    };
    for (int f = 0; f < frames; ++f) {
        const float t = frames > 1 ? float(f) / float(frames - 1) : 0.0f;
        const engine::Camera cam = cameraAt(t);
        // The sun moves during the run, so every frame redoes the RSM and the volume.
        renderer.sun().direction =
            glm::normalize(scene.lights[0].direction + glm::vec3(0.1f * std::sin(t * 6.28f), 0, 0));
        const engine::CameraMatrices m = engine::cameraMatrices(cam, float(w) / float(h));
        if (const gi::GiConfigResult r = gi::updateFromConfig(lpv, config, renderer, m); !r)
            throw std::runtime_error(r.message());
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, m, config, &profiler, &lpv);
        profiler.endFrame(cmd);
        device->endFrame();
    }
    profiler.collectPending(); // the last frames' timings
    const std::string source(rhi::timestampSourceName(profiler.gpuTimingSource()));
    std::printf("\n### %s, %s (%llu triangles, %ux%u, GI %s, timing: %s)\n\n", sceneName.c_str(),
                b.name.c_str(), (unsigned long long)scene.triangleCount(), w, h, describe(config).c_str(),
                source.c_str());
    // Commands per pass: those of the last frame that ran it (rhi::CommandCounts).
    std::printf(
        "| pass | median ms | p95 ms | predicted x360 ms | predicted ps3 ms | dispatches | draws | barriers "
        "| stages |\n|---|---|---|---|---|---|---|---|---|\n");
    double giMs = 0, fogMs = -1;
    engine::FrameProfiler::ScopePrediction fogPredicted{};
    for (size_t i : profiler.scopesInTreeOrder()) {
        const engine::ScopeInfo& s = profiler.scopes()[i];
        const engine::FrameProfiler::ScopePrediction predicted = profiler.predicted(i);
        const engine::SampleStats st = s.gpuMs.count() ? s.gpuMs.stats() : s.cpuMs.stats();
        if (s.depth == 0 && s.name == "gi") giMs = st.median;
        if (s.depth == 0 && s.path == "gi.fog") {
            fogMs = st.median;
            fogPredicted = predicted;
        }
        std::printf("| %s%s | %.2f | %.2f | %.3f | %.3f | %u | %u | %u | %u |\n",
                    std::string(2 * s.depth, ' ').c_str(), s.path.c_str(), st.median, st.p95,
                    predicted.x360.ms, predicted.ps3.ms, s.commands.dispatches, s.commands.allDraws(),
                    s.commands.barriers, s.commands.stages);
    }
    // The newest steady-state frame's commands, and its GI's dependent-pass chain.
    rhi::CommandCounts total, gi;
    profiler.forEachFrame([&](const engine::FrameProfiler::FrameRecord& r) {
        if (!r.cpuEnd || r.warmUp) return;
        total = r.commands;
        gi = {};
        for (uint32_t k = 0; k < r.sampleCount; ++k) {
            const engine::ScopeInfo& s = profiler.scopes()[r.samples[k].scope];
            if (s.depth == 0 && s.path.starts_with("gi")) gi += r.samples[k].commands;
        }
    });
    std::printf("\ncommands per steady frame: %u dispatches, %u draws (%u indexed), %u barriers; GI: %u "
                "dispatches, %u draws, %u barriers, dependent-pass chain %u stages\n",
                total.dispatches, total.allDraws(), total.drawsIndexed, total.barriers, gi.dispatches,
                gi.allDraws(), gi.barriers, gi.stages);
    const engine::SampleStats frame =
        profiler.frameGpuMs().count ? profiler.frameGpuMs() : profiler.frameCpuMs();
    std::printf("\nframe median %.2f ms; GI %.2f ms = %.1f%% of the frame (goal: at most 10%%)\n",
                frame.median, giMs, frame.median > 0 ? 100.0 * giMs / frame.median : 0.0);
    // The rule as the CryEngine 3 paper states it: GI in 10% of the frame the game targets (30 fps
    // on the consoles, 3.3 ms), here the pc profile's 60 fps, whatever this device's own frame takes.
    std::printf("GI %.2f ms = %.1f%% of the pc profile's %.2f ms frame target (its GI budget: %.2f ms)\n",
                giMs, 100.0 * giMs / pc.frameBudgetMs, pc.frameBudgetMs, pc.giBudgetMs);
    if (fogMs >= 0) {
        const gi::FogSettings fog = gi::readLpvSettings(config).fog;
        std::printf("fog (gi.fog, 1/%u resolution, %u steps): %.2f ms = %.1f%% of the frame; predicted x360 "
                    "%.3f ms, ps3 %.3f ms\n",
                    fog.resolutionDivisor, fog.steps, fogMs,
                    frame.median > 0 ? 100.0 * fogMs / frame.median : 0.0, fogPredicted.x360.ms,
                    fogPredicted.ps3.ms);
    }
    std::printf("memory:");
    for (const auto& [category, usage] : device->allocations().categories())
        if (usage.currentBytes)
            std::printf(" %s %.2f MiB;", category.c_str(), double(usage.currentBytes) / 1048576.0);
    std::printf("\n");
    if (!outDir.empty()) {
        const std::string stem = outDir + "/" + sceneName + "-" + b.name;
        engine::writeProfileOutputs(profiler, stem + "-profile");
        engine::writeScreenshot(*device, renderer, stem + "-gi-on.png");
        // The same last frame without GI (the renderer's ambient constant instead), from the
        // same camera (a run of one frame is at the path's start).
        const engine::Camera cam = cameraAt(frames > 1 ? 1.0f : 0.0f);
        const engine::CameraMatrices m = engine::cameraMatrices(cam, float(w) / float(h));
        rhi::CommandList& cmd = device->beginFrame();
        renderer.render(cmd, m, config, nullptr, nullptr); // no indirect provider: GI off
        device->endFrame();
        engine::writeScreenshot(*device, renderer, stem + "-gi-off.png");
        std::printf("wrote %s-profile/ (trace.json, frames.svg, summary.*), %s-gi-on.png, %s-gi-off.png\n",
                    stem.c_str(), stem.c_str(), stem.c_str());
    }
    std::fflush(stdout);
}

// The profiler's own cost: the Cornell box without GI, frames timed on the CPU clock from
// beginFrame to idle, with no profiler, with CPU scopes only, and with CPU and GPU scopes.
void benchProfilerOverhead(const BenchBackend& b, int frames) {
    auto device = makeDevice(b);
    engine::Config config;
    const engine::Scene scene = engine::buildBuiltinScene("cornell");
    engine::Renderer renderer(*device, 1280, 720);
    renderer.setScene(scene);
    const engine::CameraMatrices m = engine::cameraMatrices(*scene.camera, 1280.0f / 720.0f);
    const auto pc = platforms::loadPlatformProfile("pc");
    engine::ProfilerOptions cpuOnly;
    cpuOnly.gpuTiming = false;
    engine::FrameProfiler withGpu(*device, pc), withoutGpu(*device, pc, cpuOnly);
    // Per mode: median CPU time to record and submit a frame (the profiler's CPU cost shows here;
    // GL executes while recording, so there it includes GPU work) and median frame time to idle.
    const auto run = [&](engine::FrameProfiler* profiler, double& recordMs) {
        std::vector<double> ms, record;
        for (int f = 0; f < frames + 2; ++f) {
            const uint64_t t0 = platforms::nowNanoseconds();
            rhi::CommandList& cmd = device->beginFrame();
            if (profiler) profiler->beginFrame(cmd);
            renderer.render(cmd, m, config, profiler, nullptr);
            if (profiler) profiler->endFrame(cmd);
            device->endFrame();
            const uint64_t t1 = platforms::nowNanoseconds();
            device->waitIdle();
            if (f >= 2) {
                record.push_back(double(t1 - t0) / 1e6);
                ms.push_back(double(platforms::nowNanoseconds() - t0) / 1e6);
            }
        }
        recordMs = median(record);
        return median(ms);
    };
    double rNone = 0, rCpu = 0, rGpu = 0;
    const double none = run(nullptr, rNone), cpu = run(&withoutGpu, rCpu), gpu = run(&withGpu, rGpu);
    std::printf("| %-9s | %7.3f / %7.2f | %7.3f / %7.2f | %7.3f / %7.2f | %-16s |\n", b.name.c_str(), rNone,
                none, rCpu, cpu, rGpu, gpu,
                std::string(rhi::timestampSourceName(device->caps().timestampSource)).c_str());
    std::fflush(stdout);
}

// The atrium at about 100k triangles (scene detail 0.4, as the console figures assume) uploaded
// to the null device, which draws nothing but counts: built once for every RSM count below.
struct NullAtrium {
    std::unique_ptr<rhi::Device> device;
    engine::Scene scene;
    std::unique_ptr<engine::GpuScene> gpu;
    std::unique_ptr<engine::SpecularAlbedoTexture> specularAlbedo; // the RSMs' material response
};
NullAtrium nullAtrium() {
    rhi::DeviceConfig config;
    config.backend = rhi::BackendKind::Null;
    NullAtrium a;
    a.device = rhi::createDevice(config);
    a.scene = engine::buildAtrium(0.4f);
    a.gpu = std::make_unique<engine::GpuScene>(*a.device, a.scene);
    a.specularAlbedo = std::make_unique<engine::SpecularAlbedoTexture>(*a.device);
    return a;
}

// The triangles the finest cascade's sun RSM draws in `atrium` with the levels of detail
// `rsmSize` allows at the default gi.rsm_lod_texels.
uint64_t atriumRsmTriangles(const NullAtrium& atrium, uint32_t rsmSize) {
    gi::ReflectiveShadowMap rsm(*atrium.device, rsmSize);
    const glm::vec3 sun = atrium.scene.lights.at(0).direction;
    rsm.fit({atrium.scene.camera->position - glm::vec3(16.0f), 1.0f, 32}, sun);
    rhi::CommandList& cmd = atrium.device->beginFrame();
    const uint64_t triangles = rsm.record(cmd, *atrium.gpu, atrium.specularAlbedo->texture(), sun,
                                          glm::vec3(1.0f), 0.0f, gi::LpvSettings{}.rsmLodTexels);
    atrium.device->endFrame();
    return triangles;
}

// The triangles a spot light's RSM (one map) and a point light's cube RSM (six faces) draw in
// `atrium` at `rsmSize` with the default levels of detail: a light 8 m over the court, the spot
// looking down at the columns (as the RSM level-of-detail test places it), reaching the far corner
// of a 32 m volume around it.
struct LightRsmTriangles {
    uint64_t spot = 0, cube = 0;
};
LightRsmTriangles atriumLightRsmTriangles(const NullAtrium& atrium, uint32_t rsmSize) {
    gi::ReflectiveShadowMap rsm(*atrium.device, rsmSize, gi::RsmLight::Spot);
    engine::Light light = engine::atriumCourtSpot();
    const float reach = std::sqrt(3.0f) * 16.0f + 8.0f;
    const float lodTexels = gi::LpvSettings{}.rsmLodTexels;
    LightRsmTriangles out;
    rhi::CommandList& cmd = atrium.device->beginFrame();
    out.spot = rsm.recordSpot(cmd, *atrium.gpu, atrium.specularAlbedo->texture(), light, reach, lodTexels);
    light.type = engine::LightType::Point;
    for (uint32_t f = 0; f < gi::kCubeFaces; ++f)
        out.cube += rsm.recordCubeFace(cmd, *atrium.gpu, atrium.specularAlbedo->texture(), light, f, reach,
                                       lodTexels);
    atrium.device->endFrame();
    return out;
}

void consolePrediction() {
    gi::LpvSettings s;
    s.cascades = 1;
    s.gridSize = 32;
    s.rsmSize = 128;
    s.vplCount = 1024;
    s.iterations = 6;
    s.shFormat = gi::ShFormat::Rgba8;
    // The calibration counts the diffuse lookup the published times measured: no glossy lobes, and
    // no geometry volume (none of its passes is counted), so no faces in the lookup either.
    s.glossy = false;
    s.occlusion = false;
    const uint64_t pixels = 1280 * 720;
    const auto x360 = platforms::loadPlatformProfile("x360"), ps3 = platforms::loadPlatformProfile("ps3");
    double sx = 0, sp = 0;
    // Their Xbox 360 injection resolved into one slice at a time (talk, slide 40): per slice here.
    for (const engine::WorkCounts& w :
         {gi::rsmWork(s, 100000), gi::vplClusterWork(s), gi::injectWork(s, 0, gi::VolumeDraw::PerSlice),
          gi::propagateWork(s), gi::lookupWork(s, pixels)}) {
        sx += engine::predictCost(w, x360.throughput).ms;
        sp += engine::predictCost(w, ps3.throughput).ms;
    }
    std::printf("\nCryEngine 3 console setup (32^3, RSM 128^2, 6 iterations, 1 cascade, RGBA8, 1280x720): "
                "predicted GI "
                "%.2f ms on Xbox 360 (published 3.5 ms), %.2f ms on PS3 (published 3.4 ms)\n",
                sx, sp);
    // A spot light with its own RSM (gi.light_rsms=1): its RSM and clustering, and its VPLs in
    // the injection of that one cascade. A point light with a cube RSM (gi.point_light_rsms=1): six
    // such RSMs and six VPL sets. Their triangles are counted as this engine draws them (levels of
    // detail, only what each map's frustum holds) in the 100k-triangle atrium.
    const NullAtrium atrium = nullAtrium();
    const LightRsmTriangles lightTriangles = atriumLightRsmTriangles(atrium, s.rsmSize);
    const auto lightMs = [&](const platforms::PlatformProfile& p, uint32_t rsms, uint64_t triangles) {
        return engine::predictCost(gi::lightRsmWork(s, rsms, triangles), p.throughput).ms +
               engine::predictCost(gi::injectWork(s, rsms * gi::spotLightVplSlots(s)), p.throughput).ms -
               engine::predictCost(gi::injectWork(s), p.throughput).ms;
    };
    std::printf("  plus one spot light RSM of 128^2 (gi.light_rsms=1; a spot over the atrium's court, "
                "%llu triangles): %.2f ms on Xbox 360, %.2f ms on PS3\n",
                (unsigned long long)lightTriangles.spot, lightMs(x360, 1, lightTriangles.spot),
                lightMs(ps3, 1, lightTriangles.spot));
    std::printf("  plus one point light cube RSM of 6 x 128^2 (gi.point_light_rsms=1; the same light as a "
                "point light, %llu triangles): %.2f ms on Xbox 360, %.2f ms on PS3\n",
                (unsigned long long)lightTriangles.cube, lightMs(x360, gi::kCubeFaces, lightTriangles.cube),
                lightMs(ps3, gi::kCubeFaces, lightTriangles.cube));

    // The frames part's settings at console formats, every feature of this engine that runs: 3 cascades of
    // 32^3, 8 iterations, 2 bounces (in the finest cascade, gi.bounce_cascades' default), occlusion (camera
    // surfels, 160 x 90 samples: marks in the finest cascade, areas in the coarse ones), RGBA8,
    // RSM 128^2, a 100k-triangle scene. Every cascade every frame, and as gi.budget_policy=adapt's
    // first step runs it (coarse cascades every 2 frames: the busiest frame updates one of them).
    gi::LpvSettings c = s;
    c.cascades = 3;
    c.iterations = 8;
    c.occlusion = true;
    c.bounces = 2;
    c.glossy = true;
    // Where gi.budget_policy=adapt stops: every knob at its floor (gi/GiScheduler.h's limits).
    const gi::GiSchedulerLimits limits;
    gi::LpvSettings f = c;
    f.iterations = limits.minIterations;
    f.rsmSize = limits.minRsmSize;
    f.bounces = 1;
    struct Pass {
        const char* name;
        engine::WorkCounts work, atFloor;
        uint32_t perFrame, perFrameStaggered; // runs in a frame: every cascade / coarse every 2 frames
    };
    // The lookup and the glossy march run on a quarter of the pixels (gi.resolution=half, the
    // default; a sixteenth at the floor); the lighting pass rebuilds the rest, and that work is GI's.
    const uint64_t lowPixels = (1280 / 2) * (720 / 2);
    // The CryEngine 3 setup above drew its scenes' meshes in full; this engine's RSMs draw levels of
    // detail, fewer the coarser the map (counted for the finest cascade, the coarse ones draw fewer).
    const uint64_t rsmTriangles = atriumRsmTriangles(atrium, c.rsmSize),
                   floorRsmTriangles = atriumRsmTriangles(atrium, f.rsmSize);
    std::printf(
        "\nThe finest cascade's RSM in a 100k-triangle atrium draws %llu triangles at %u^2 and %llu at "
        "%u^2 (levels of detail within gi.rsm_lod_texels=%.2f of a texel)\n",
        (unsigned long long)rsmTriangles, c.rsmSize, (unsigned long long)floorRsmTriangles, f.rsmSize,
        double(gi::LpvSettings{}.rsmLodTexels));
    const uint64_t floorPixels =
        uint64_t(1280 / limits.maxResolutionDivisor) * (720 / limits.maxResolutionDivisor);
    // A coarse cascade's geometry volume: the light's surfels, and with gi.coarse_camera_occlusion
    // the camera's areas.
    const uint64_t cameraSamples = gi::GeometryVolume::cameraSampleCount(1280, 720);
    const auto coarseOcclusion = [&](const gi::LpvSettings& settings) {
        engine::WorkCounts w = gi::occlusionWork(settings, 0);
        if (settings.cameraAreas()) w += gi::cameraAreasWork(settings, cameraSamples);
        return w;
    };
    const Pass passes[] = {
        {"rsm (per cascade)", gi::rsmWork(c, rsmTriangles), gi::rsmWork(f, floorRsmTriangles), 3, 2},
        {"vpl (per cascade)", gi::vplClusterWork(c), gi::vplClusterWork(f), 3, 2},
        {"occlusion, finest (camera surfels)", gi::occlusionWork(c, cameraSamples),
         gi::occlusionWork(f, cameraSamples), 1, 1},
        {"occlusion, coarse cascade (with gi.coarse_camera_occlusion, its camera areas)", coarseOcclusion(c),
         coarseOcclusion(f), 2, 1},
        {"inject (per cascade)", gi::injectWork(c), gi::injectWork(f), 3, 2},
        {"propagate (per cascade)", gi::propagateWork(c), gi::propagateWork(f), 3, 2},
        {"bounces (finest cascade, gi.bounce_cascades=1)", gi::bounceWork(c), gi::bounceWork(f),
         c.bounceCascades, c.bounceCascades},
        {"lookup (up to 2 of 3 cascades per pixel)", gi::lookupWork(c, lowPixels),
         gi::lookupWork(f, floorPixels), 1, 1},
        {"glossy", gi::glossyWork(lowPixels), gi::glossyWork(floorPixels), 1, 1},
        {"bilateral rebuild to 1280x720 (gi.rebuild, runs in render.lighting)",
         engine::indirectRebuildWork(pixels), engine::indirectRebuildWork(pixels), 1, 1},
    };
    std::printf(
        "\nThe frames part's settings on the consoles (every feature at PC size: 3 x 32^3 cascades, 8 "
        "iterations, 2 bounces, occlusion, glossy; with RGBA8, RSM 128^2, 1280x720, gi.resolution=half; "
        "6 MiB of GI memory, twice the consoles' 3 MiB), predicted ms per run of each pass; at adapt's floor "
        "(%u iterations, RSM %u^2, lookup every %u pixels per axis, 1 bounce):\n\n"
        "| pass | runs per frame | x360 | ps3 | x360 at floor | ps3 at floor |\n|---|---|---|---|---|---|\n",
        f.iterations, f.rsmSize, limits.maxResolutionDivisor);
    double all[2] = {}, staggered[2] = {};
    for (const Pass& pass : passes) {
        const double x = engine::predictCost(pass.work, x360.throughput).ms;
        const double y = engine::predictCost(pass.work, ps3.throughput).ms;
        const double fx = engine::predictCost(pass.atFloor, x360.throughput).ms;
        const double fy = engine::predictCost(pass.atFloor, ps3.throughput).ms;
        std::printf("| %s | %u (%u) | %.2f | %.2f | %.2f | %.2f |\n", pass.name, pass.perFrame,
                    pass.perFrameStaggered, x, y, fx, fy);
        all[0] += x * pass.perFrame, all[1] += y * pass.perFrame;
        staggered[0] += x * pass.perFrameStaggered, staggered[1] += y * pass.perFrameStaggered;
    }
    // At the floor the coarse cascades update every 4 frames, each in two halves on two frames of
    // its own (GiScheduler.h's CascadeWork): the busiest frame runs the finest cascade, the larger
    // half of one coarse update, and the per-pixel passes.
    double atFloor[2] = {};
    for (int p = 0; p < 2; ++p) {
        const platforms::Throughput& t = p == 0 ? x360.throughput : ps3.throughput;
        const auto ms = [&](const engine::WorkCounts& w) { return engine::predictCost(w, t).ms; };
        const double light = ms(gi::rsmWork(f, floorRsmTriangles)) + ms(gi::vplClusterWork(f));
        const double fine = light + ms(gi::occlusionWork(f, cameraSamples)) + ms(gi::injectWork(f)) +
                            ms(gi::propagateWork(f)) + ms(gi::bounceWork(f));
        const double coarseVolume = ms(coarseOcclusion(f)) + ms(gi::injectWork(f)) + ms(gi::propagateWork(f));
        atFloor[p] = fine + std::max(light, coarseVolume) + ms(gi::lookupWork(f, floorPixels)) +
                     ms(gi::glossyWork(floorPixels)) + ms(engine::indirectRebuildWork(pixels));
    }
    std::printf(
        "\n(runs in brackets: coarse cascades every 2 frames, gi.budget_policy=adapt's first step)\n");
    for (int p = 0; p < 2; ++p)
        std::printf("PC settings on %s: predicted GI %.2f ms with every cascade every frame, %.2f ms with "
                    "coarse cascades every 2 frames, %.2f ms at adapt's floor (goal: at most 3.3 ms)\n",
                    p == 0 ? "x360" : "ps3", all[p], staggered[p], atFloor[p]);
}

// The console preset the engine ships (gi/presets/console.toml) as the game runs it: the null
// device (which counts every pass's work), the full atrium at 1280x720 flown and lit as the frames
// part does, the profiler predicting each frame's GI on the console's profile and the budget
// scheduler watching it (the preset sets gi.budget_policy=adapt). The first frame makes every
// cascade at once; after it the coarse cascades take turns.
void consolePresetFlight(const char* console, bool printPasses, bool fog = false) {
    const auto profile = platforms::loadPlatformProfile(console);
    rhi::DeviceConfig deviceConfig;
    deviceConfig.backend = rhi::BackendKind::Null;
    const auto device = rhi::createDevice(deviceConfig);
    engine::Config config;
    config.loadFile(LPV_CONSOLE_PRESET);
    config.applyOverride("gi.cell_size=1.0", "bench"); // the atrium's, as in the frames part
    if (fog) config.applyOverride("fog.enabled=true", "bench");
    const engine::Scene scene = engine::buildAtrium();
    const uint32_t w = 1280, h = 720;
    engine::Renderer renderer(*device, w, h);
    renderer.setScene(scene);
    engine::FrameProfiler profiler(*device, profile);
    gi::LightPropagationVolume lpv(*device, profile);
    const engine::Camera start = *scene.camera;
    // With fog, adapt walks every GI knob before the fog's: long enough for it to settle.
    const int frames = fog ? 320 : 64;
    for (int f = 0; f < frames; ++f) {
        const float t = float(f) / float(frames - 1);
        renderer.sun().direction =
            glm::normalize(scene.lights[0].direction + glm::vec3(0.1f * std::sin(t * 6.28f), 0, 0));
        const engine::CameraMatrices m = engine::cameraMatrices(
            engine::cameraOnPath("flythrough", scene.bounds, start, t * 0.25f), float(w) / float(h));
        if (const gi::GiConfigResult r = gi::updateFromConfig(lpv, config, renderer, m, &profiler); !r)
            throw std::runtime_error(r.message());
        rhi::CommandList& cmd = device->beginFrame();
        profiler.beginFrame(cmd);
        renderer.render(cmd, m, config, &profiler, &lpv);
        profiler.endFrame(cmd);
        device->endFrame();
    }
    profiler.collectPending();
    double first = -1, worst = 0;
    std::vector<double> later;
    profiler.forEachFrame([&](const engine::FrameProfiler::FrameRecord& r) {
        if (!r.checked) return;
        if (first < 0)
            first = r.check.giBudgetedMs;
        else
            later.push_back(r.check.giBudgetedMs);
    });
    for (double ms : later)
        worst = std::max(worst, ms);
    const gi::LpvSettings s = gi::readLpvSettings(config);
    std::printf(
        "\n%s%s: predicted GI %.2f ms on the first frame (every cascade made, its second bounce left "
        "to the next), then %.2f ms median and %.2f "
        "ms at most over %zu frames (goal: at most %.1f ms: %s); adapt took %u steps; GI memory %.2f MiB "
        "allocated of %.2f MiB (%.2f planned before the start, a spot light's RSM included)\n",
        console, fog ? " with fog.enabled=true" : "", first, median(later), worst, later.size(),
        profile.giBudgetMs,
        fog                           ? "while adapt steps, see the settled frames"
        : worst <= profile.giBudgetMs ? "fits"
                                      : "does not fit",
        lpv.schedule().stepsInEffect, double(profiler.allocations().bytesIn("gi")) / 1048576.0,
        double(profile.giMemoryBudgetBytes) / 1048576.0, double(gi::giBytes(gi::giResources(s))) / 1048576.0);
    if (fog) {
        // The last 64 frames, after adapt's steps.
        const std::vector<double> settled(later.end() - std::min<size_t>(later.size(), 64), later.end());
        const double settledWorst = *std::max_element(settled.begin(), settled.end());
        std::printf(
            "%s with fog.enabled=true, the last %zu frames: GI %.2f ms median, %.2f ms at most (goal: at "
            "most %.1f ms: %s)\n",
            console, settled.size(), median(settled), settledWorst, profile.giBudgetMs,
            settledWorst <= profile.giBudgetMs ? "fits" : "does not fit");
        double fogMs = 0;
        for (size_t i = 0; i < profiler.scopes().size(); ++i)
            if (profiler.scopes()[i].path == "gi.fog") fogMs = profiler.predicted(i).active.ms;
        std::printf(
            "%s: the fog (gi.fog) predicted %.2f ms in the last frame that ran it, at 1/%u resolution "
            "and %u steps (fog.resolution and fog.steps as adapt left them)\n",
            console, fogMs, lpv.settings().fog.resolutionDivisor, lpv.settings().fog.steps);
    }
    if (!printPasses) return;
    // Each pass's predicted ms in the last frame that ran it: the same work on either profile. A
    // frame runs cascade0, one of the two coarse cascades, the lookup, the march and the rebuild.
    std::printf(
        "\nEach pass's predicted ms per run (the same work on both consoles; a frame runs cascade0, one "
        "of cascade1 and cascade2, lookup, glossy and gi.rebuild):\n\n");
    std::printf("| pass | predicted x360 ms | predicted ps3 ms |\n|---|---|---|\n");
    for (size_t i = 0; i < profiler.scopes().size(); ++i) {
        const engine::ScopeInfo& scope = profiler.scopes()[i];
        // Passes only: a parent's row would be one frame's, with one of the two coarse cascades.
        const bool parent =
            std::any_of(profiler.scopes().begin(), profiler.scopes().end(),
                        [&](const engine::ScopeInfo& o) { return o.path.starts_with(scope.path + "/"); });
        if (scope.path.rfind("gi", 0) != 0 || parent) continue;
        const engine::FrameProfiler::ScopePrediction predicted = profiler.predicted(i);
        std::printf("| %s | %.3f | %.3f |\n", scope.path.c_str(), predicted.x360.ms, predicted.ps3.ms);
    }
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"GI benchmark: propagation kernels, analytic lights, frames with every GI feature on, the "
                 "profiler's overhead and the console prediction, per backend"};
    std::vector<BenchBackend> backends;
    addBackendsOption(app, backends);
    std::vector<std::string> scenes = {"cornell", "atrium"};
    app.add_option("--scenes", scenes, "Scenes of the frames part, comma-separated")
        ->delimiter(',')
        ->check(CLI::IsMember({"cornell", "atrium"}))
        ->capture_default_str();
    std::vector<std::string> partList = {"propagation", "lights", "frames", "profiler", "console"};
    app.add_option("--parts", partList, "Parts to run, comma-separated")
        ->delimiter(',')
        ->check(CLI::IsMember(partList))
        ->capture_default_str();
    int runs = 5, frames = 12;
    int kernelRuns = 101; // propagation: a run takes ~50 ms, and this machine's noise needs many
    app.add_option("--kernel-runs", kernelRuns, "Propagation runs (medians of)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    app.add_option("--runs", runs, "Runs of the lights part")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    app.add_option("--frames", frames, "Frames per scene and backend (frames and profiler parts)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    std::string outDir;
    app.add_option("--out", outDir, "Folder for the frames' traces, charts and screenshots");
    FrameOverrides overrides;
    app.add_option(
           "--config", overrides.files,
           "A settings file (TOML, as the game's --config) for the frames part, after the benchmark's "
           "own settings and before --set: --config gi/presets/console.toml (repeatable)")
        ->check(CLI::ExistingFile);
    app.add_option("--set", overrides.assignments,
                   "Override a setting in the frames part, after the benchmark's own and --config's: --set "
                   "gi.glossy_max_roughness=0.6 (repeatable)");
    if (const std::optional<int> exit = parseCommandLine(app, argc, argv)) return *exit;
    // A wrong key or value fails before any device starts, naming the setting.
    try {
        // As the frames part sets them, so that what the settings refuse together (gi.bounces=3
        // with gi.occlusion=false) fails here too, not after a device started; --config and --set
        // are the frames part's alone, so without it the values are only checked one by one.
        const bool framesPart = std::find(partList.begin(), partList.end(), "frames") != partList.end();
        for (const std::string& scene : framesPart ? scenes : std::vector<std::string>{}) {
            const engine::Config config = frameSettings(scene, overrides);
            if (const std::string refusal = framesRefusal(config); !refusal.empty()) {
                std::fprintf(stderr, "error: %s\n", refusal.c_str());
                return 2;
            }
            (void)gi::readLpvSettings(config);
        }
        (void)frameSettings("", overrides);
    } catch (const engine::ConfigError& e) {
        std::string message = e.what();
        // The game's hint; lpv_bench has no --help-config.
        if (const size_t hint = message.find(" (--help-config lists them all)"); hint != std::string::npos)
            message.erase(hint);
        // The game's --help-config lists the game's settings; the frame size, backends, scenes and
        // platform here are the benchmark's own options, not settings.
        if (message.find("unknown setting") == std::string::npos) {
            std::fprintf(stderr, "error: %s\n", message.c_str());
            return 2;
        }
        std::fprintf(
            stderr,
            "error: %s\nlpv_bench --config and --set take the settings its frames part reads (gi.*, and the "
            "renderer's render.* but for the frame size, backend and window settings, which are "
            "the game's): the frame is 1280x720 on the backends of --backends and the "
            "scenes of --scenes, on the pc profile\n",
            message.c_str());
        return 2;
    }
    const auto want = [&](const char* part) {
        return std::find(partList.begin(), partList.end(), part) != partList.end();
    };
    // The folder is made before any part runs: a run of minutes should not end in a write error.
    if (!outDir.empty()) {
        if (!want("frames")) {
            std::fprintf(stderr,
                         "error: --out: only the frames part writes files, and --parts leaves it out\n");
            return 2;
        }
        try {
            platforms::Platform::createDirectories(outDir);
            platforms::Platform::checkWritable(outDir + "/.lpv_bench_check");
        } catch (const std::exception& e) {
            std::fprintf(stderr, "error: --out: %s\n", e.what());
            return 2;
        }
    }
    int failures = 0;
    if (want("propagation")) {
        std::printf(
            "## Propagation, 32^3 x 8 iterations, RGBA16F (median of %d runs, ms; shipped: bounded partial\n"
            "## sums, as for one cascade; shell: with the shell of several cascades; speedups: medians of\n"
            "## the per-run ratios baseline / shipped, all timed in the same frame; quartiles of those "
            "ratios)\n\n",
            kernelRuns);
        std::printf("| backend   | shipped ms | shell ms | baseline ms | speedup | quartiles    | shell   | "
                    "quartiles    | max rel diff | timing source    |\n");
        std::printf("|-----------|------------|----------|-------------|---------|--------------|---------|-"
                    "-------------|--------------|------------------|\n");
        for (const auto& b : backends) {
            try {
                benchPropagation(b, kernelRuns);
            } catch (const std::exception& e) {
                std::printf("| %-9s | failed: %s\n", b.name.c_str(), e.what());
                ++failures;
            }
        }
    }
    if (want("lights")) {
        std::printf("\n## Analytic lights pass, 32^3 RGBA16F (median of %d, ms)\n\n", runs);
        std::printf("| backend   | 128 lights | 1024 lights | timing source    |\n|---|---|---|---|\n");
        for (const auto& b : backends) {
            try {
                benchAnalyticLights(b, runs);
            } catch (const std::exception& e) {
                std::printf("| %-9s | failed: %s\n", b.name.c_str(), e.what());
                ++failures;
            }
        }
    }
    if (want("frames")) {
        std::printf("\n## Frames (GI on, %d frames, median)\n", frames);
        for (const std::string& file : overrides.files)
            std::printf("--config %s\n", file.c_str());
        for (const std::string& o : overrides.assignments)
            std::printf("--set %s\n", o.c_str());
        // The frames part hands the GI no profiler, so the scheduler has no cost to judge: it times
        // the settings as written.
        const engine::Config settings = frameSettings("", overrides); // the scene sets only the cell size
        if (gi::readLpvSettings(settings).budgetPolicy == gi::GiBudgetPolicy::Adapt)
            std::printf(
                "gi.budget_policy = adapt (%s) changes nothing here: the frames part times the settings "
                "as written\n",
                settings.origin(settingNamed("gi.budget_policy")).c_str());
        for (const std::string& scene : scenes)
            for (const auto& b : backends) {
                try {
                    benchFrames(b, scene, frames, outDir, overrides);
                } catch (const std::exception& e) {
                    std::printf("%s on %s failed: %s\n", scene.c_str(), b.name.c_str(), e.what());
                    ++failures;
                }
            }
    }
    if (want("profiler")) {
        std::printf("\n## Profiler overhead (Cornell box, GI off, 1280x720, median frame ms of %d)\n\n",
                    frames);
        std::printf("| backend   | no profiler | CPU scopes | CPU+GPU scopes | timing source |\n");
        std::printf("|---|---|---|---|---|\n");
        for (const auto& b : backends) {
            try {
                benchProfilerOverhead(b, frames);
            } catch (const std::exception& e) {
                std::printf("| %-9s | failed: %s\n", b.name.c_str(), e.what());
                ++failures;
            }
        }
    }
    if (want("console")) {
        consolePrediction();
        std::printf(
            "\n## The console preset (gi/presets/console.toml: 3 x 24^3 cascades, coarse ones every 2 "
            "frames, 8 iterations, 2 bounces, occlusion, glossy, RGBA8, RSM 128^2, 1024 VPLs, "
            "gi.resolution=quarter) through the pipeline on the null device, the full atrium at "
            "1280x720 flown as in the frames part\n");
        consolePresetFlight("x360", false);
        consolePresetFlight("ps3", true);
        // Fog on top of the preset: adapt lowers fog.resolution and fog.steps after the GI's knobs.
        consolePresetFlight("x360", false, true);
        consolePresetFlight("ps3", false, true);
    }
    return failures ? 1 : 0;
}
