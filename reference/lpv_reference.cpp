// lpv_reference: renders the path-traced ground truth of a scene for the engine's camera and writes
// the diffuse-indirect, direct and combined radiance as PFM (and EXR), and with --fog-density the
// light a medium scatters toward the camera and its transmittance. See docs/reference-renderer.md.
#include "reference/PathTracer.h"
#include "reference/Pfm.h"

#include "engine/scene/SceneLoading.h"

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <glm/vector_relational.hpp>

#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr const char* kPhysics = R"(What it computes (linear radiance per pixel, RGB float):
  indirect  diffuse-indirect radiance, what render.debug_view=indirect shows: albedo x indirect
            irradiance / pi, light that bounced 1..N times (--bounces) before the visible surface
  direct    direct diffuse radiance: albedo x direct irradiance / pi
  combined  their sum
Physics:
  Surfaces are glTF's metallic-roughness model as the engine shows its diffuse part: a Lambertian
  base, albedo = glTF base colour factor x base colour texture (sRGB decoded, bilinear, repeat) x
  (1 - metallic) (metals have no diffuse part), under a specular layer that leaves the base
  1 - F(v.h) of the light (fresnel_mix: Schlick's F, F0 = mix(0.04, base colour, metallic), h the
  half vector of the directions the light arrives and leaves along), at every bounce and at the
  visible surface (--surfaces lambertian: the base alone). The layer's own reflection, and
  emission, are off; the sky is black. Geometry is two-sided; instance transforms apply (normals by
  the inverse transpose); the shading normal is the interpolated vertex normal.
  Directional light (the first one, the engine's sun): intensity x color is the irradiance E (lux)
  on a surface facing it; a lit surface leaves albedo x E x max(cos, 0) / pi.
  Point light: intensity x color is radiant intensity (W/sr): E = I cos / d^2, times
  clamp(1 - (d/range)^4, 0, 1) when range > 0. Spot light: the same times
  smoothstep(cos(outer), cos(inner), dot(-toLight, direction)) (the engine's punctualArrival).
  Every light casts a shadow ray (Embree).
Camera: the engine's (cameraMatrices: right-handed, depth 0..1, image row 0 at the top); the
  scene's own camera, else the game's default, with --camera-pos/--camera-target/--fov overrides.
Estimator: next-event estimation at every path vertex, cosine-weighted bounces, a jittered sample
  per pixel per pass; each pixel has its own random stream (seeded by --seed and the pixel index),
  so the image is the same for any thread count.
Fog (--fog-density > 0; the engine's fog.* settings): a medium along the camera rays only, from
  the eye to the visible surface (or --fog-miss-distance, or with --fog-miss-bounds where the ray
  leaves the scene's bounds, as the engine's march), single scattering. sigma_t(y) = density x
  exp(-height_falloff x max(y - base_height, 0)) per metre, grey; sigma_s = albedo x sigma_t;
  Henyey-Greenstein phase function of g = anisotropy. It scatters toward the camera
  fog_sun       the sun's light: E_sun x phase, shadowed by the scene (a shadow ray), not
                attenuated by the medium on its way (the engine's sun reaches fog through its shadow
                map only; --fog-attenuate-sun attenuates it)
  fog_indirect  the light surfaces leave, bounced 1..N times (--bounces), as an LPV holds it: the
                surfaces' direct + indirect radiance, arriving unattenuated by the medium
  fog           their sum
  each integrated along the ray with the transmittance from the camera; and
  transmittance exp(-optical depth) from the camera to the visible surface (grey)
  fogged        combined x transmittance + fog: the diffuse image the camera sees through the fog
  Surfaces and their light ignore the medium: the other images are the same with fog as without.
  Distances are drawn in proportion to sigma_t x transmittance, stratified over the pixel's
  samples (--fog-samples per camera sample), each with a sun shadow ray and one phase-sampled path.
Files: PREFIX_indirect.pfm, PREFIX_direct.pfm, PREFIX_combined.pfm (little endian, rows bottom to
  top); with --exr also .exr; with --geometry PREFIX_position.pfm, PREFIX_normal.pfm and
  PREFIX_hit.pfm (1: geometry, 0: sky) of the ray through each pixel's centre; with fog
  PREFIX_fog_sun.pfm, PREFIX_fog_indirect.pfm, PREFIX_fog.pfm, PREFIX_transmittance.pfm and
  PREFIX_fogged.pfm (and .exr with --exr).)";

glm::vec3 parseVec3(const std::string& text, const std::string& option) {
    glm::vec3 v;
    char c1 = 0, c2 = 0;
    std::istringstream in(text);
    if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !in.eof())
        throw CLI::ValidationError(option, "expected x,y,z, got '" + text + "'");
    return v;
}

} // namespace

int main(int argc, char** argv) {
    using namespace lpv;
    CLI::App app{"lpv_reference: a path-traced ground truth (Embree) for LPV Engine's scenes"};
    app.footer(kPhysics);
    std::string scenePath = "cornell", out, cameraPos, cameraTarget;
    float fov = 0.0f;
    bool exr = false, geometry = false, quiet = false;
    std::string fogAlbedo = "0.9,0.9,0.9";
    reference::TraceSettings settings;
    reference::Medium& fog = settings.medium;
    app.add_option("scene,--scene", scenePath,
                   "Built-in scene (cornell, atrium, lights) or a .gltf/.glb path")
        ->capture_default_str();
    app.add_option("--out", out,
                   "Output prefix: writes PREFIX_indirect.pfm, PREFIX_direct.pfm, PREFIX_combined.pfm")
        ->required();
    app.add_option("--width", settings.width, "Image width")
        ->capture_default_str()
        ->check(CLI::Range(1u, 16384u));
    app.add_option("--height", settings.height, "Image height")
        ->capture_default_str()
        ->check(CLI::Range(1u, 16384u));
    app.add_option("--spp", settings.samplesPerPixel, "Samples per pixel")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1u << 20));
    app.add_option("--bounces", settings.bounces,
                   "Diffuse bounces in the indirect (1: light -> A -> visible)")
        ->capture_default_str()
        ->check(CLI::Range(1u, 3u));
    app.add_option("--surfaces", settings.surfaces, lpv::reference::RayScene::kSurfacesHelp)
        ->transform(CLI::CheckedTransformer(lpv::reference::RayScene::surfaceNames()))
        ->option_text("TEXT:{gltf,lambertian}=gltf");
    app.add_option("--seed", settings.seed, "Random seed")->capture_default_str();
    app.add_option("--threads", settings.threads, "Threads (0: all cores)")->capture_default_str();
    app.add_option("--camera-pos", cameraPos, "Camera position x,y,z (default: the scene's camera)");
    app.add_option("--camera-target", cameraTarget, "Point the camera looks at, x,y,z");
    app.add_option("--fov", fov, "Vertical field of view in degrees")->check(CLI::Range(1.0f, 179.0f));
    app.add_flag("--exr", exr, "Also write PREFIX_*.exr");
    app.add_flag("--geometry", geometry,
                 "Also write the visible surfaces' position, normal and hit mask (PFM)");
    app.add_flag("--quiet", quiet, "No progress line on stderr");
    app.add_option("--fog-density", fog.density,
                   "Fog extinction coefficient sigma_t at the base height, 1/m (fog.density; 0: no fog)")
        ->capture_default_str()
        ->check(CLI::Range(0.0f, 1000.0f));
    app.add_option("--fog-albedo", fogAlbedo, "Fog single-scattering albedo r,g,b in [0, 1] (fog.albedo)")
        ->capture_default_str();
    app.add_option("--fog-anisotropy", fog.anisotropy, "Henyey-Greenstein g (fog.anisotropy)")
        ->capture_default_str()
        ->check(CLI::Range(-0.99f, 0.99f));
    app.add_option("--fog-height-falloff", fog.heightFalloff,
                   "Exponential height fog falloff, 1/m (fog.height_falloff; 0: homogeneous)")
        ->capture_default_str()
        ->check(CLI::Range(0.0f, 100.0f));
    app.add_option("--fog-base-height", fog.baseHeight, "Height where sigma_t = density, m (fog.base_height)")
        ->capture_default_str();
    app.add_option("--fog-miss-distance", fog.missDistance,
                   "How far a ray that meets no surface goes through the fog, m")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_flag("--fog-miss-bounds", fog.missAtSceneBounds,
                 "A ray that meets no surface stops where it leaves the scene's bounds (the engine's march)");
    app.add_option("--fog-samples", settings.mediumSamples, "Fog distance samples per camera sample")
        ->capture_default_str()
        ->check(CLI::Range(1u, 1024u));
    app.add_flag("--fog-attenuate-sun", fog.attenuateSunlight,
                 "Attenuate the sun's light by the fog on its way to the scattering points");
    CLI11_PARSE(app, argc, argv);

    try {
        const engine::Scene scene = engine::loadScene(scenePath);
        engine::Camera camera = engine::defaultCamera(scene);
        if (!cameraPos.empty()) camera.position = parseVec3(cameraPos, "--camera-pos");
        if (!cameraTarget.empty())
            camera.forward = glm::normalize(parseVec3(cameraTarget, "--camera-target") - camera.position);
        if (fov > 0.0f) camera.verticalFov = glm::radians(fov);
        fog.albedo = parseVec3(fogAlbedo, "--fog-albedo");
        if (glm::any(glm::lessThan(fog.albedo, glm::vec3(0.0f))) ||
            glm::any(glm::greaterThan(fog.albedo, glm::vec3(1.0f))))
            throw CLI::ValidationError("--fog-albedo", "each component must be in [0, 1]");
        settings.progress = !quiet;

        const auto start = std::chrono::steady_clock::now();
        const reference::TracedImage image = reference::trace(scene, camera, settings);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!quiet)
            std::fprintf(stderr, "lpv_reference: %s %ux%u, %u spp, %u bounce(s)%s: %.2f s\n",
                         scene.name.c_str(), settings.width, settings.height, settings.samplesPerPixel,
                         settings.bounces, fog.present() ? ", fog" : "", seconds);

        const std::filesystem::path parent = std::filesystem::path(out).parent_path();
        if (!parent.empty()) std::filesystem::create_directories(parent);
        const auto write = [&](const std::string& name, const std::vector<glm::vec3>& pixels, bool withExr) {
            reference::writePfm(out + "_" + name + ".pfm", image.width, image.height, pixels);
            if (withExr) reference::writeExr(out + "_" + name + ".exr", image.width, image.height, pixels);
        };
        write("indirect", image.indirect, exr);
        write("direct", image.direct, exr);
        write("combined", image.combined, exr);
        if (geometry) {
            std::vector<glm::vec3> hit(image.hit.size());
            for (size_t i = 0; i < hit.size(); ++i)
                hit[i] = glm::vec3(float(image.hit[i]));
            write("position", image.position, false);
            write("normal", image.normal, false);
            write("hit", hit, false);
        }
        if (fog.present()) {
            write("fog_sun", image.fogSun, exr);
            write("fog_indirect", image.fogIndirect, exr);
            write("fog", image.fog, exr);
            write("transmittance", image.transmittance, exr);
            write("fogged", image.fogged, exr);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "lpv_reference: %s\n", e.what());
        return 1;
    }
    return 0;
}
