// The fidelity benchmark: the engine's indirect light against the path tracer's (lpv_reference),
// per scene and backend. Prints, per scene: mean ratio per channel, relative RMSE (RMSE / mean
// reference luminance over pixels with geometry), the same after the best single scale, the mean
// ratio on ceilings, floors and walls, and the share of pixels over 3x the reference; with --out,
// writes each view as engine | reference side by side (PNG, one exposure for both) and both
// images as linear radiance (PFM: <scene>-<backend>.pfm, <scene>-reference.pfm) for analysis.
//
// Then, when its scene (cornell-sun) is among --scenes, the fog (issue 48): the engine's
// render.debug_view=fog against the reference's medium (FidelityScenes.h, fidelityFog), the same
// figures for the fog, its sun part and its indirect part (EngineFog.h), and with --out the three
// side by side. --fog-spp 0 leaves it out.
//
//   lpv_fidelity [--backends=vulkan,gl-egl] [--scenes=cornell,...] [--spp=N] [--bounces=1..3]
//                [--surfaces=gltf|lambertian]
//                [--fog-spp=N] [--fog-density=D] [--fog-anisotropy=G] [--out=DIR] [--set key=value ...]
#include "../BenchBackends.h"
#include "../BenchCommandLine.h"
#include "EngineFog.h"
#include "EngineIndirect.h"
#include "FidelityMetrics.h"
#include "FidelityScenes.h"

#include "engine/ImageFile.h"
#include "engine/config/Config.h"
#include "engine/scene/SceneLoading.h"
#include "gi/adapter/LpvConfig.h"
#include "platforms/Clock.h"
#include "platforms/Platform.h"
#include "reference/PathTracer.h"
#include "reference/Pfm.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::bench;

namespace {

// Both images at one exposure (the reference's mean luminance to 0.18), Reinhard, sRGB.
void writeSideBySide(const std::string& path, uint32_t w, uint32_t h, const std::vector<glm::vec3>& engine,
                     const std::vector<glm::vec3>& reference) {
    double sum = 0.0;
    for (const glm::vec3& r : reference)
        sum += 0.2126 * r.r + 0.7152 * r.g + 0.0722 * r.b;
    const float exposure = sum > 0.0 ? float(0.18 * double(reference.size()) / sum) : 1.0f;
    const auto encode = [&](float v) {
        v *= exposure;
        v = v / (1.0f + v);
        v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
        return uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
    };
    const uint32_t gap = 4, width = 2 * w + gap;
    std::vector<uint8_t> rgba(size_t(width) * h * 4, 255);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            for (int side = 0; side < 2; ++side) {
                const glm::vec3 c = (side == 0 ? engine : reference)[size_t(y) * w + x];
                uint8_t* o = &rgba[(size_t(y) * width + x + side * (w + gap)) * 4];
                o[0] = encode(c.r), o[1] = encode(c.g), o[2] = encode(c.b), o[3] = 255;
            }
    engine::writePng(path, width, h, rgba);
}

std::string ratio(float r) {
    if (r < 0.0f) return "-";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", r);
    return buf;
}

// The scene's GI settings, then the caller's.
engine::Config sceneConfig(const FidelityScene& fs, uint32_t bounces,
                           const std::vector<std::string>& assignments) {
    engine::Config config;
    config.applyOverride("gi.enabled=true", "lpv_fidelity");
    config.applyOverride("gi.bounces=" + std::to_string(bounces), "lpv_fidelity");
    // The light as a GPU renders it by default: gi.gather = auto turns the gather off on the CPU
    // rasterizers the benchmark runs on here (--set gi.gather=off for the propagation alone).
    config.applyOverride("gi.gather=on", "lpv_fidelity");
    for (const std::string& s : fs.settings)
        config.applyOverride(s, "lpv_fidelity's scene " + fs.name);
    for (const std::string& s : assignments)
        config.applyOverride(s);
    return config;
}

// The fog, its sun part and its indirect part against the reference's, per backend.
void compareFog(const FidelityScene& fs, const FidelityFog& fog, const std::vector<BenchBackend>& backends,
                const reference::TraceSettings& traced, int frames, const engine::Config& config,
                const std::string& outDir) {
    const engine::Scene scene = engine::loadScene(fs.source);
    const engine::Camera camera = scene.camera.value_or(engine::Camera{});
    reference::TraceSettings ts = traced;
    ts.width = fog.width, ts.height = fog.height;
    ts.medium = fog.medium;
    const uint64_t t0 = platforms::nowNanoseconds();
    const reference::TracedImage ref = reference::trace(scene, camera, ts);
    const double traceMs = double(platforms::nowNanoseconds() - t0) / 1e6;
    const reference::Medium& m = fog.medium;
    std::printf(
        "\n## Fog in %s against the path tracer (%ux%u, %u spp, %u bounce%s)\n\ndensity %.3g/m, albedo "
        "%.2g/%.2g/%.2g, g %.2g, height falloff %.3g; fog.steps %u, fog.resolution=full; sun part: "
        "gi.enabled=false, indirect part: the difference\n\n",
        fs.name.c_str(), fog.width, fog.height, ts.samplesPerPixel, ts.bounces, ts.bounces > 1 ? "s" : "",
        m.density, m.albedo.r, m.albedo.g, m.albedo.b, m.anisotropy, m.heightFalloff,
        gi::lpvSettingsFrom(config).fog.steps);
    std::printf("| part | backend | mean ratio r/g/b | rel. RMSE | after scale (x) | reference mean |\n"
                "|---|---|---|---|---|---|\n");
    for (const BenchBackend& b : backends) {
        auto device = makeDevice(b);
        const EngineFogParts e =
            renderEngineFogParts(*device, scene, camera, fog.width, fog.height, config, fog.medium, frames);
        const struct {
            const char *name, *image; // as printed; the side-by-side image's suffix
            const std::vector<glm::vec3>& engine;
            const std::vector<glm::vec3>& reference;
        } parts[] = {{"fog", "fog", e.total, ref.fog},
                     {"sun", "fog-sun", e.sun, ref.fogSun},
                     {"indirect", "fog-indirect", e.indirect, ref.fogIndirect}};
        for (const auto& p : parts) {
            const FidelityFigures f = compareIndirect(p.engine, p.reference, {ref.normal, ref.hit});
            std::printf("| %s | %s | %.2f/%.2f/%.2f | %.3f | %.3f (%.2f) | %.4f |\n", p.name, b.name.c_str(),
                        f.meanRatio.r, f.meanRatio.g, f.meanRatio.b, f.relativeRmse, f.relativeRmseScaled,
                        f.bestScale, f.referenceMean);
            if (!outDir.empty())
                writeSideBySide(outDir + "/" + fs.name + "-" + p.image + "-" + b.name + ".png", fog.width,
                                fog.height, p.engine, p.reference);
        }
        std::fflush(stdout);
    }
    std::fprintf(stderr, "%s fog: reference traced in %.1f s\n", fs.name.c_str(), traceMs / 1000.0);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"GI fidelity: the engine's indirect light against a path-traced reference (lpv_reference), "
                 "per scene and backend"};
    std::vector<BenchBackend> backends;
    addBackendsOption(app, backends);
    // Vulkan and gl-egl unless --backends says otherwise (gl-osmesa draws the same pixels as gl-egl).
    backends = {allBenchBackends()[0], allBenchBackends()[1]};
    std::vector<std::string> names = fidelitySceneNames();
    app.add_option("--scenes", names, "Scenes, comma-separated")
        ->delimiter(',')
        ->check(CLI::IsMember(fidelitySceneNames()))
        ->capture_default_str();
    uint32_t spp = 256, bounces = 1;
    reference::RayScene::Surfaces surfaces = reference::RayScene::Surfaces::Gltf;
    int frames = 3;
    app.add_option("--spp", spp, "Reference samples per pixel (the built-in cornell's: 4 times as many)")
        ->check(CLI::Range(1, 1 << 20))
        ->capture_default_str();
    app.add_option("--bounces", bounces,
                   "Diffuse bounces in the reference's indirect light (the engine runs with gi.bounces set "
                   "to the same)")
        ->check(CLI::Range(1, 3))
        ->capture_default_str();
    app.add_option("--surfaces", surfaces, reference::RayScene::kSurfacesHelp)
        ->transform(CLI::CheckedTransformer(reference::RayScene::surfaceNames()))
        ->option_text("TEXT:{gltf,lambertian}=gltf");
    app.add_option("--frames", frames, "Engine frames before the read-back")->check(CLI::Range(1, 100));
    FidelityFog fog = fidelityFog();
    uint32_t fogSpp = 256;
    app.add_option("--fog-spp", fogSpp,
                   "Reference samples per pixel for the fog comparison (run when its scene, " + fog.scene +
                       ", is among --scenes; 0: not run)")
        ->check(CLI::Range(0, 1 << 20))
        ->capture_default_str();
    app.add_option("--fog-density", fog.medium.density, "The fog comparison's fog.density (1/m)")
        ->check(CLI::Range(0.001f, 10.0f))
        ->capture_default_str();
    app.add_option("--fog-anisotropy", fog.medium.anisotropy, "The fog comparison's fog.anisotropy (g)")
        ->check(CLI::Range(-0.95f, 0.95f))
        ->capture_default_str();
    std::string outDir;
    app.add_option("--out", outDir,
                   "Folder for the side-by-side images (engine | reference, PNG) and both images (PFM)");
    std::vector<std::string> assignments;
    app.add_option("--set", assignments,
                   "A setting for every scene, after the scene's own: --set gi.iterations=16");
    if (const std::optional<int> exit = parseCommandLine(app, argc, argv)) return *exit;
    if (!outDir.empty()) platforms::Platform::createDirectories(outDir);

    const std::vector<FidelityScene> all = fidelityScenes(LPV_FIDELITY_SCENES);
    int failures = 0;
    std::printf("## GI fidelity against the path tracer (%u bounce%s, %u spp%s)\n\n", bounces,
                bounces > 1 ? "s" : "", spp,
                surfaces == reference::RayScene::Surfaces::Lambertian ? ", Lambertian surfaces" : "");
    for (const std::string& s : assignments)
        std::printf("--set %s\n", s.c_str());
    std::printf(
        "| scene | backend | mean ratio r/g/b | rel. RMSE | after scale (x) | ceilings | floors | walls | "
        ">3x |\n|---|---|---|---|---|---|---|---|---|\n");
    for (const FidelityScene& fs : all) {
        if (std::find(names.begin(), names.end(), fs.name) == names.end()) continue;
        try {
            const engine::Scene scene = engine::loadScene(fs.source);
            const engine::Camera camera = scene.camera.value_or(engine::Camera{});
            reference::TraceSettings ts;
            ts.width = fs.width, ts.height = fs.height, ts.samplesPerPixel = spp * fs.sampleFactor;
            ts.bounces = bounces;
            ts.surfaces = surfaces;
            const uint64_t t0 = platforms::nowNanoseconds();
            const reference::TracedImage ref = reference::trace(scene, camera, ts);
            const double traceMs = double(platforms::nowNanoseconds() - t0) / 1e6;
            if (!outDir.empty())
                reference::writePfm(outDir + "/" + fs.name + "-reference.pfm", fs.width, fs.height,
                                    ref.indirect);
            for (const BenchBackend& b : backends) {
                const engine::Config config = sceneConfig(fs, bounces, assignments);
                auto device = makeDevice(b);
                const std::vector<glm::vec3> engineImage =
                    renderEngineIndirect(*device, scene, camera, fs.width, fs.height, config, frames);
                const FidelityFigures f = compareIndirect(engineImage, ref.indirect, {ref.normal, ref.hit});
                std::printf("| %s | %s | %.2f/%.2f/%.2f | %.2f | %.2f (%.2f) | %s | %s | %s | %.1f%% |\n",
                            fs.name.c_str(), b.name.c_str(), f.meanRatio.r, f.meanRatio.g, f.meanRatio.b,
                            f.relativeRmse, f.relativeRmseScaled, f.bestScale,
                            ratio(f.orientation.ceilings).c_str(), ratio(f.orientation.floors).c_str(),
                            ratio(f.orientation.walls).c_str(), 100.0 * f.shareOver3x);
                std::fflush(stdout);
                if (!outDir.empty()) {
                    writeSideBySide(outDir + "/" + fs.name + "-" + b.name + ".png", fs.width, fs.height,
                                    engineImage, ref.indirect);
                    reference::writePfm(outDir + "/" + fs.name + "-" + b.name + ".pfm", fs.width, fs.height,
                                        engineImage);
                }
            }
            std::fprintf(stderr, "%s: reference traced in %.1f s (%u spp)\n", fs.name.c_str(),
                         traceMs / 1000.0, ts.samplesPerPixel);
        } catch (const std::exception& e) {
            std::printf("| %s | failed: %s |\n", fs.name.c_str(), e.what());
            ++failures;
        }
    }
    for (const FidelityScene& fs : all) {
        if (fogSpp == 0 || fs.name != fog.scene ||
            std::find(names.begin(), names.end(), fs.name) == names.end())
            continue;
        try {
            reference::TraceSettings ts;
            ts.samplesPerPixel = fogSpp, ts.bounces = bounces, ts.surfaces = surfaces;
            compareFog(fs, fog, backends, ts, frames, sceneConfig(fs, bounces, assignments), outDir);
        } catch (const std::exception& e) {
            std::printf("| fog | failed: %s |\n", e.what());
            ++failures;
        }
    }
    return failures ? 1 : 0;
}
