// The path-traced reference against closed forms: a white furnace (the geometric series per
// bounce), the form factor of two parallel squares, the sun's and the punctual lights' direct
// terms (exact), determinism across thread counts, and PFM round trips; the fog medium (issue 48)
// against its closed forms: transmittance, the sun's single scattering (with and without shadow),
// the in-scattering of a uniform radiance field, and the Henyey-Greenstein phase function.
//
// Noise and bounds: the furnace is noise-free (every path in a closed box of one albedo under a
// uniform source carries the same value), and so are the direct terms (no sampling in them). The
// form factor is a Bernoulli estimate per path: a ray from the receiver hits the emitter with
// probability F ~ 0.2, so one path's relative standard deviation is sqrt((1 - F) / F) = 2.0; with
// 32 x 32 points x 512 paths (524288 paths) the standard error is 2.0 / 724 = 0.28%, and the 1%
// bound is 3.6 standard errors (the points are cell centres, whose quadrature error is ~1e-4).
// The medium's estimates are noise-free where the light scattered is the same all along a ray (an
// unshadowed sun, a uniform radiance field): distances are drawn in proportion to sigma_t x
// transmittance, so every sample carries albedo x (1 - T) x the same light.
#include "reference/Medium.h"
#include "reference/PathTracer.h"
#include "reference/Pfm.h"

#include "engine/scene/MeshBuilder.h"
#include "engine/scene/SceneLoading.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

using namespace lpv;
using namespace lpv::reference;

namespace {

constexpr double kPi = 3.14159265358979323846;
const glm::vec3 kUp{0.0f, 1.0f, 0.0f};

// Every surface (or only one instance's) receives the same direct irradiance: a light source with a
// known answer, standing in for SceneLights. It has no direction, so its surfaces are Lambertian
// (RayScene::Surfaces::Lambertian).
class UniformIrradiance : public DirectLighting {
public:
    explicit UniformIrradiance(glm::vec3 e, int32_t onlyInstance = -1) : e_(e), only_(onlyInstance) {}
    glm::vec3 irradiance(const SurfacePoint& p, const RayScene&, glm::vec3) const override {
        if (p.layered) throw std::logic_error("UniformIrradiance lights Lambertian surfaces only");
        return only_ < 0 || p.instance == uint32_t(only_) ? e_ : glm::vec3(0.0f);
    }

private:
    glm::vec3 e_;
    int32_t only_;
};

engine::Scene sceneWith(glm::vec3 albedo) {
    engine::Scene scene;
    scene.name = "test";
    scene.materials.push_back({"surface", glm::vec4(albedo, 1.0f)});
    return scene;
}

engine::Camera lookingAt(glm::vec3 position, glm::vec3 target, float fovDegrees) {
    engine::Camera camera;
    camera.position = position;
    camera.forward = glm::normalize(target - position);
    camera.up =
        std::abs(camera.forward.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    camera.verticalFov = glm::radians(fovDegrees);
    return camera;
}

// View factor between parallel, directly opposed rectangles a x b at distance c (Howell's catalogue,
// C-11).
double parallelRectangles(double a, double b, double c) {
    const double x = a / c, y = b / c, x2 = 1.0 + x * x, y2 = 1.0 + y * y;
    return 2.0 / (kPi * x * y) *
           (std::log(std::sqrt(x2 * y2 / (x2 + y2 - 1.0))) +
            x * std::sqrt(y2) * std::atan(x / std::sqrt(y2)) +
            y * std::sqrt(x2) * std::atan(y / std::sqrt(x2)) - x * std::atan(x) - y * std::atan(y));
}

} // namespace

TEST_CASE("reference: a white furnace gives the geometric series per bounce") {
    const float a = 0.5f, e0 = 2.0f;
    engine::Scene scene = sceneWith(glm::vec3(a));
    engine::MeshBuilder builder(scene);
    builder.begin("box", 0);
    builder.box({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}, true);
    builder.finish();
    const RayScene rays(scene, RayScene::Surfaces::Lambertian);
    const UniformIrradiance source{glm::vec3(e0)};
    const engine::Camera camera = lookingAt({0.1f, 0.2f, 0.3f}, {-0.5f, -0.3f, -1.0f}, 90.0f);

    TraceSettings settings;
    settings.width = settings.height = 16;
    settings.samplesPerPixel = 8;
    for (uint32_t bounces = 1; bounces <= 3; ++bounces) {
        CAPTURE(bounces);
        settings.bounces = bounces;
        const TracedImage image = trace(rays, source, camera, settings);
        double series = 0.0;
        for (uint32_t k = 1; k <= bounces; ++k)
            series += std::pow(double(a), double(k));
        const double expected = a / kPi * e0 * series;
        double mean = 0.0, worst = 0.0;
        for (size_t i = 0; i < image.indirect.size(); ++i) {
            REQUIRE(image.hit[i] == 1);
            mean += image.indirect[i].g / double(image.indirect.size());
            worst = std::max(worst, std::abs(image.indirect[i].g / expected - 1.0));
            CHECK(image.direct[i].r == doctest::Approx(a / kPi * e0).epsilon(1e-5));
        }
        CHECK(mean == doctest::Approx(expected).epsilon(0.01));
        CHECK(worst < 0.01);
        std::printf("furnace, %u bounce(s): indirect %.6f, expected %.6f (worst pixel %.2e off)\n", bounces,
                    mean, expected, worst);
    }
}

TEST_CASE("reference: the form factor between two parallel unit squares") {
    const float a = 0.6f, e0 = 3.0f;
    engine::Scene scene = sceneWith(glm::vec3(a));
    engine::MeshBuilder builder(scene);
    builder.begin("receiver", 0); // instance 0, at y = 0, facing up
    builder.quad({0.0f, 0.0f, 1.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f});
    builder.finish();
    builder.begin("emitter", 0); // instance 1, at y = 1, facing down
    builder.quad({0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    builder.finish();
    const RayScene rays(scene, RayScene::Surfaces::Lambertian);
    // Only the emitter is lit, so it leaves a E0 / pi, and the receiver's incident irradiance from
    // it (one bounce) is a E0 F(point); its mean over the receiver is a E0 F.
    const UniformIrradiance source(glm::vec3(e0), 1);

    constexpr uint32_t kGrid = 32, kPaths = 512;
    double sum = 0.0;
    for (uint32_t j = 0; j < kGrid; ++j)
        for (uint32_t i = 0; i < kGrid; ++i) {
            SurfacePoint p;
            p.position = {(float(i) + 0.5f) / kGrid, 0.0f, (float(j) + 0.5f) / kGrid};
            p.normal = p.geometricNormal = {0.0f, 1.0f, 0.0f};
            p.albedo = glm::vec3(a);
            sum += indirectIrradiance(rays, source, p, {0.0f, 1.0f, 0.0f}, 1, kPaths, j * kGrid + i).g;
        }
    const double f = sum / (kGrid * kGrid) / (a * e0);
    const double expected = parallelRectangles(1.0, 1.0, 1.0);
    std::printf("parallel unit squares at distance 1: F = %.5f, closed form %.5f\n", f, expected);
    CHECK(expected == doctest::Approx(0.19982).epsilon(1e-4));
    CHECK(f == doctest::Approx(expected).epsilon(0.01));
}

TEST_CASE("reference: the sun's direct term on a floor is albedo x E x cos x (1 - F) / pi") {
    const glm::vec3 albedo(0.6f, 0.5f, 0.4f);
    engine::Scene scene = sceneWith(albedo);
    engine::MeshBuilder builder(scene);
    builder.begin("floor", 0);
    builder.quad({-50.0f, 0.0f, 50.0f}, {100.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -100.0f});
    builder.finish();
    engine::Light sun;
    sun.type = engine::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.2f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);

    TraceSettings settings;
    settings.width = settings.height = 24;
    settings.samplesPerPixel = 4;
    const engine::Camera camera = lookingAt({0.0f, 2.0f, 1.0f}, {0.0f, 0.0f, -1.0f}, 60.0f);
    const TracedImage image = trace(scene, camera, settings);
    const RayScene plain(scene, RayScene::Surfaces::Lambertian);
    const TracedImage lambertian = trace(plain, SceneLights(scene), camera, settings);
    const glm::vec3 lambert = albedo * sun.color * sun.intensity * -sun.direction.y / float(kPi);
    float least = 1.0f, most = 0.0f;
    for (size_t i = 0; i < image.direct.size(); ++i) {
        REQUIRE(image.hit[i] == 1);
        // glTF's dielectric layer (F0 4%) keeps 1 - F(v.h) for the base: at the pixel's centre,
        // which its four samples are within 2e-3 of.
        const glm::vec3 v = glm::normalize(camera.position - image.position[i]);
        const glm::vec3 h = glm::normalize(v - sun.direction);
        const float share = 1.0f - (0.04f + 0.96f * std::pow(1.0f - glm::dot(v, h), 5.0f));
        least = std::min(least, share);
        most = std::max(most, share);
        for (int c = 0; c < 3; ++c) {
            CHECK(lambertian.direct[i][c] == doctest::Approx(lambert[c]).epsilon(1e-5));
            CHECK(image.direct[i][c] == doctest::Approx(lambert[c] * share).epsilon(2e-3));
            CHECK(image.indirect[i][c] == 0.0f); // nothing else to bounce off
            CHECK(image.combined[i][c] == image.direct[i][c]);
        }
        CHECK(image.normal[i].y == doctest::Approx(1.0f));
        CHECK(image.position[i].y == doctest::Approx(0.0f));
    }
    std::printf("sun on a floor: direct %.6f (red), Lambertian %.6f; the layer keeps %.4f-%.4f\n",
                image.direct[0].r, lambert.r, least, most);
}

TEST_CASE("reference: one bounce between layered surfaces, against a quadrature of the same integral") {
    // A sunlit floor square and a point above it, both under glTF's dielectric layer: the path
    // tracer's estimate against a midpoint quadrature over the square of
    // albedo / pi x E cos_sun x (1 - F at the floor) x (1 - F at the point) x cos x cos / r^2.
    const float albedo = 0.6f;
    engine::Scene scene = sceneWith(glm::vec3(albedo));
    engine::MeshBuilder builder(scene);
    builder.begin("floor", 0);
    builder.quad({-0.5f, 0.0f, 0.5f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f});
    builder.finish();
    engine::Light sun;
    sun.type = engine::LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.6f, -1.0f, 0.3f));
    sun.intensity = 2.0f;
    scene.lights.push_back(sun);
    const RayScene rays(scene);
    const SceneLights lights(scene);

    SurfacePoint p;
    p.position = {0.2f, 0.6f, 0.7f};
    p.normal = p.geometricNormal = glm::normalize(glm::vec3(-0.2f, -1.0f, -0.6f));
    p.layered = true;
    p.f0 = glm::vec3(0.04f);
    // Seen at a grazing angle, where the layer takes most.
    const glm::vec3 toViewer = glm::normalize(glm::vec3(0.9f, -0.35f, 0.1f));
    REQUIRE(glm::dot(toViewer, p.normal) > 0.0f);
    const auto keeps = [](glm::vec3 toLight, glm::vec3 out) {
        const glm::vec3 h = glm::normalize(toLight + out);
        return 1.0 - (0.04 + 0.96 * std::pow(1.0 - double(glm::dot(out, h)), 5.0));
    };
    constexpr int kCells = 400;
    double expected = 0.0, lambertian = 0.0;
    for (int j = 0; j < kCells; ++j)
        for (int i = 0; i < kCells; ++i) {
            const glm::vec3 x(-0.5f + (float(i) + 0.5f) / kCells, 0.0f, -0.5f + (float(j) + 0.5f) / kCells);
            const glm::vec3 d = x - p.position;
            const float r = glm::length(d);
            const glm::vec3 dir = d / r;
            const double cosP = glm::dot(p.normal, dir), cosX = -dir.y;
            if (cosP <= 0.0) continue;
            const double radiance = albedo / kPi * sun.intensity * -sun.direction.y;
            const double geometry = cosP * cosX / (double(r) * r) / (double(kCells) * kCells);
            expected += radiance * keeps(-sun.direction, -dir) * keeps(dir, toViewer) * geometry;
            lambertian += radiance * geometry;
        }
    const double traced = indirectIrradiance(rays, lights, p, toViewer, 1, 1u << 17, 7).g;
    std::printf("one layered bounce: %.6f traced, %.6f by quadrature (%.6f without the layers)\n", traced,
                expected, lambertian);
    CHECK(traced == doctest::Approx(expected).epsilon(0.01));
    CHECK(expected < 0.97 * lambertian); // the layers take more than the test's tolerance
}

TEST_CASE("reference: point and spot lights follow the engine's punctualArrival, shadowed") {
    engine::Scene scene = sceneWith(glm::vec3(0.5f));
    engine::MeshBuilder builder(scene);
    builder.begin("floor", 0);
    builder.quad({-10.0f, 0.0f, 10.0f}, {20.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -20.0f});
    builder.finish();
    builder.begin("blocker", 0); // a small square over x = 5
    builder.quad({4.5f, 1.0f, -0.5f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    builder.finish();
    engine::Light point;
    point.type = engine::LightType::Point;
    point.position = {0.0f, 2.0f, 0.0f};
    point.intensity = 10.0f;
    point.color = {1.0f, 0.5f, 0.25f};
    point.range = 6.0f;
    engine::Light spot = point;
    spot.type = engine::LightType::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.innerConeAngle = 0.3f;
    spot.outerConeAngle = 0.6f;
    spot.range = 0.0f;
    const RayScene rays(scene);

    const auto at = [](glm::vec3 position) {
        SurfacePoint p;
        p.position = position;
        p.normal = p.geometricNormal = {0.0f, 1.0f, 0.0f};
        return p;
    };
    const auto smoothstep = [](float e0, float e1, float x) {
        const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
        return t * t * (3.0f - 2.0f * t);
    };
    {
        engine::Scene lit = scene;
        lit.lights = {point};
        const SceneLights lights(lit);
        const glm::vec3 p(1.5f, 0.0f, 0.5f), toLight = point.position - p;
        const float d = glm::length(toLight), cosine = toLight.y / d, ratio = d / point.range;
        const float expected = point.intensity * cosine / (d * d) * (1.0f - ratio * ratio * ratio * ratio);
        CHECK(lights.irradiance(at(p), rays, kUp).r == doctest::Approx(expected).epsilon(1e-5));
        CHECK(lights.irradiance(at(p), rays, kUp).b == doctest::Approx(0.25f * expected).epsilon(1e-5));
        // Beyond the range window, and below the blocker's shadow.
        CHECK(lights.irradiance(at({6.5f, 0.0f, 0.0f}), rays, kUp).r == 0.0f);
        CHECK(lights.irradiance(at({5.0f, 1e-3f, 0.0f}), rays, kUp).r > 0.0f);
        lit.lights[0].position = {5.0f, 2.0f, 0.0f};
        const SceneLights above(lit);
        CHECK(above.irradiance(at({5.0f, 0.0f, 0.0f}), rays, kUp).r == 0.0f);
    }
    {
        engine::Scene lit = scene;
        lit.lights = {spot};
        const SceneLights lights(lit);
        for (float x : {0.0f, 0.5f, 1.0f, 1.5f, 2.5f}) {
            CAPTURE(x);
            const glm::vec3 p(x, 0.0f, 0.0f), toLight = spot.position - p;
            const float d = glm::length(toLight), cosine = toLight.y / d;
            const float cone = smoothstep(std::cos(spot.outerConeAngle), std::cos(spot.innerConeAngle),
                                          glm::dot(-toLight / d, spot.direction));
            const float expected = spot.intensity * cosine / (d * d) * cone;
            CHECK(lights.irradiance(at(p), rays, kUp).r == doctest::Approx(expected).epsilon(1e-5));
        }
    }
}

TEST_CASE("reference: albedo is base colour factor x sRGB texture x (1 - metallic), under a layer") {
    engine::Scene scene = sceneWith(glm::vec3(1.0f));
    scene.materials[0].baseColor = {0.5f, 1.0f, 0.8f, 1.0f};
    scene.materials[0].metallic = 0.25f;
    scene.materials[0].baseColorTexture = 0;
    scene.textures.push_back({"texel", 1, 1, {128, 64, 255, 255}, true});
    engine::MeshBuilder builder(scene);
    builder.begin("floor", 0);
    builder.quad({-1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f});
    builder.finish();
    const RayScene rays(scene);
    const std::optional<SurfacePoint> p = rays.intersect({0.2f, 1.0f, 0.1f}, {0.0f, -1.0f, 0.0f});
    REQUIRE(p.has_value());
    const auto linear = [](float c) {
        return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    };
    CHECK(p->albedo.r == doctest::Approx(0.5f * linear(128.0f / 255.0f) * 0.75f).epsilon(1e-5));
    CHECK(p->albedo.g == doctest::Approx(linear(64.0f / 255.0f) * 0.75f).epsilon(1e-5));
    CHECK(p->albedo.b == doctest::Approx(0.8f * 0.75f).epsilon(1e-5));
    // The specular layer's F0, as the engine's lighting pass: mix(4%, base colour, metallic).
    CHECK(p->layered);
    CHECK(p->f0.g == doctest::Approx(0.75f * 0.04f + 0.25f * linear(64.0f / 255.0f)).epsilon(1e-5));
    CHECK(p->f0.b == doctest::Approx(0.75f * 0.04f + 0.25f * 0.8f).epsilon(1e-5));
    CHECK(p->position.y == doctest::Approx(0.0f));
    // Seen from below, both normals face down.
    const std::optional<SurfacePoint> below = rays.intersect({0.2f, -1.0f, 0.1f}, {0.0f, 1.0f, 0.0f});
    REQUIRE(below.has_value());
    CHECK(below->normal.y == doctest::Approx(-1.0f));
    CHECK(below->geometricNormal.y == doctest::Approx(-1.0f));
}

TEST_CASE("reference: the same seed gives the same image on 1 and 2 threads") {
    const engine::Scene scene = engine::loadScene("cornell");
    const engine::Camera camera = engine::defaultCamera(scene);
    TraceSettings settings;
    settings.width = settings.height = 32;
    settings.samplesPerPixel = 4;
    settings.bounces = 2;
    settings.medium.density = 0.1f;
    settings.medium.anisotropy = 0.4f;
    settings.threads = 1;
    const TracedImage one = trace(scene, camera, settings);
    settings.threads = 2;
    const TracedImage two = trace(scene, camera, settings);
    CHECK(one.indirect == two.indirect);
    CHECK(one.direct == two.direct);
    CHECK(one.hit == two.hit);
    CHECK(one.fogSun == two.fogSun);
    CHECK(one.fogIndirect == two.fogIndirect);
    CHECK(one.transmittance == two.transmittance);
    CHECK(one.fogged == two.fogged);
    settings.seed = 2;
    const TracedImage other = trace(scene, camera, settings);
    CHECK(other.indirect != one.indirect);
    CHECK(other.fogIndirect != one.fogIndirect);
    double indirect = 0.0;
    for (const glm::vec3& v : one.indirect)
        indirect += v.r;
    CHECK(indirect > 0.0);
}

TEST_CASE("reference: PFM files round-trip") {
    const uint32_t w = 3, h = 2;
    std::vector<glm::vec3> pixels;
    for (uint32_t i = 0; i < w * h; ++i)
        pixels.push_back({float(i), -1.5f * float(i), 1e-3f + float(i * i)});
    const std::string path =
        (std::filesystem::temp_directory_path() / "lpv_reference_roundtrip.pfm").string();
    writePfm(path, w, h, pixels);
    const PfmImage back = readPfm(path);
    CHECK(back.width == w);
    CHECK(back.height == h);
    CHECK(back.pixels == pixels);
    std::filesystem::remove(path);
    CHECK_THROWS(readPfm(path));
}

namespace {

// Henyey-Greenstein's cumulative distribution of the cosine: P(cos <= mu).
double henyeyGreensteinCdf(double mu, double g) {
    if (g == 0.0) return (mu + 1.0) / 2.0;
    return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
}

// The optical depth of the engine's height fog (constant at and below the base height) by the
// midpoint rule, independent of the closed form under test.
double integratedDepth(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double distance) {
    constexpr int kSteps = 20000;
    double sum = 0.0;
    for (int k = 0; k < kSteps; ++k) {
        const double y = origin.y + (k + 0.5) * distance / kSteps * direction.y;
        sum += medium.density * std::exp(-medium.heightFalloff * std::max(y - medium.baseHeight, 0.0));
    }
    return sum * distance / kSteps;
}

// A wall in the plane z = -depth, facing the origin, far wider than any ray here reaches.
engine::Scene wallAt(float depth) {
    engine::Scene scene = sceneWith(glm::vec3(0.5f));
    engine::MeshBuilder builder(scene);
    builder.begin("wall", 0);
    builder.quad({-100.0f, -100.0f, -depth}, {200.0f, 0.0f, 0.0f}, {0.0f, 200.0f, 0.0f});
    builder.finish();
    return scene;
}

engine::Light sunLight(glm::vec3 direction, glm::vec3 irradiance) {
    engine::Light sun;
    sun.type = engine::LightType::Directional;
    sun.direction = glm::normalize(direction);
    sun.color = irradiance;
    sun.intensity = 1.0f;
    return sun;
}

} // namespace

TEST_CASE("reference: the Henyey-Greenstein phase function integrates to 1 and is sampled by its pdf") {
    const glm::vec3 incident = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    for (float g : {0.0f, 0.3f, 0.6f, -0.5f, 0.9f}) {
        CAPTURE(g);
        // 2 pi x the integral over the cosine (midpoint rule; the peak at g = 0.9 is 0.01 wide).
        constexpr int kSteps = 100000;
        double integral = 0.0;
        for (int k = 0; k < kSteps; ++k)
            integral += henyeyGreenstein(float(-1.0 + (k + 0.5) * 2.0 / kSteps), g);
        integral *= 2.0 * kPi * 2.0 / kSteps;
        CHECK(integral == doctest::Approx(1.0).epsilon(1e-4));

        // A histogram of the sampled cosines against the distribution's bins, within 5 standard
        // errors per bin; the mean cosine of Henyey-Greenstein is g.
        constexpr int kSamples = 100000, kBins = 20;
        std::vector<int> bins(kBins, 0);
        double meanCosine = 0.0, meanSide = 0.0;
        std::mt19937 random(7);
        const auto uniform = [&] { return float(random() >> 8) / 16777216.0f; };
        const glm::vec3 side = glm::normalize(glm::cross(incident, glm::vec3(0.0f, 1.0f, 0.0f)));
        for (int k = 0; k < kSamples; ++k) {
            const float u1 = uniform(), u2 = uniform();
            const glm::vec3 w = sampleHenyeyGreenstein(incident, g, u1, u2);
            REQUIRE(glm::length(w) == doctest::Approx(1.0f).epsilon(1e-5));
            const double c = glm::dot(w, incident);
            bins[std::clamp(int((c + 1.0) / 2.0 * kBins), 0, kBins - 1)]++;
            meanCosine += c / kSamples;
            meanSide += glm::dot(w, side) / kSamples;
        }
        for (int b = 0; b < kBins; ++b) {
            const double p = henyeyGreensteinCdf(-1.0 + 2.0 * (b + 1) / kBins, g) -
                             henyeyGreensteinCdf(-1.0 + 2.0 * b / kBins, g);
            CAPTURE(b);
            CHECK(std::abs(bins[size_t(b)] / double(kSamples) - p) <
                  5.0 * std::sqrt(p * (1.0 - p) / kSamples));
        }
        // Var(cos) = (1 - g^2) / 3, as the second Legendre moment of Henyey-Greenstein is g^2.
        CHECK(std::abs(meanCosine - g) < 5.0 * std::sqrt((1.0 - g * g) / 3.0 / kSamples));
        CHECK(std::abs(meanSide) < 5.0 / std::sqrt(double(kSamples)));
    }
}

TEST_CASE("reference: transmittance to a wall is exp(-sigma_t d); distances are drawn in proportion to it") {
    const float depth = 6.0f, sigma = 0.15f;
    const engine::Scene scene = wallAt(depth); // RayScene keeps a reference to it
    const RayScene rays(scene, RayScene::Surfaces::Lambertian);
    const UniformIrradiance dark{glm::vec3(0.0f)};
    Medium medium;
    medium.density = sigma;
    for (float angle : {0.0f, 0.4f, -0.9f}) {
        CAPTURE(angle);
        const glm::vec3 w(std::sin(angle), 0.0f, -std::cos(angle));
        const double d = depth / std::cos(double(angle));
        const MediumRadiance r = scatteredAlongRay(rays, dark, medium, glm::vec3(0.0f), w, 1, 4, 1);
        CHECK(r.distance == doctest::Approx(d).epsilon(1e-5));
        CHECK(r.transmittance == doctest::Approx(std::exp(-sigma * d)).epsilon(1e-5));
        CHECK(r.sun == glm::vec3(0.0f));
        CHECK(r.indirect == glm::vec3(0.0f)); // the wall is dark
    }
    // A ray that meets nothing goes on to Medium::missDistance: through infinite fog, no light.
    const glm::vec3 away(0.0f, 0.0f, 1.0f);
    CHECK(scatteredAlongRay(rays, dark, medium, glm::vec3(0.0f), away, 1, 1, 1).transmittance == 0.0f);
    medium.missDistance = 10.0f;
    CHECK(scatteredAlongRay(rays, dark, medium, glm::vec3(0.0f), away, 1, 1, 1).transmittance ==
          doctest::Approx(std::exp(-sigma * 10.0)).epsilon(1e-6));

    // Or, as the engine's march, it stops where it leaves the scene's bounds: here x and z in
    // [-5, 5], y in [0, 3] (a floor and a small square above it), nothing from outside them.
    engine::Scene room = sceneWith(glm::vec3(0.5f));
    engine::MeshBuilder builder(room);
    builder.begin("floor", 0);
    builder.quad({-5.0f, 0.0f, 5.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -10.0f});
    builder.quad({0.0f, 3.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f});
    builder.finish();
    const RayScene roomRays(room, RayScene::Surfaces::Lambertian);
    medium.missAtSceneBounds = true;
    for (auto [origin, w, d] : {std::tuple{glm::vec3(-2.0f, 1.0f, 0.0f), glm::vec3(1.0f, 0.0f, 0.0f), 7.0},
                                {glm::vec3(-2.0f, 1.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 2.0},
                                {glm::vec3(-2.0f, 4.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 0.0}}) {
        const MediumRadiance r = scatteredAlongRay(roomRays, dark, medium, origin, w, 1, 1, 1);
        CHECK(r.distance == doctest::Approx(d));
        CHECK(r.transmittance == doctest::Approx(std::exp(-sigma * d)).epsilon(1e-6));
    }

    // Height fog: the closed form against the midpoint rule, from above and below the base height,
    // up, down (crossing it both ways) and level; and the inverse that draws distances:
    // 1 - T(t(u)) = u (1 - T(d)).
    Medium fog;
    fog.density = 0.3f;
    fog.heightFalloff = 0.7f;
    fog.baseHeight = 1.0f;
    for (glm::vec3 origin : {glm::vec3(0.5f, 2.0f, -1.0f), glm::vec3(0.5f, 0.2f, -1.0f)})
        for (glm::vec3 w : {glm::vec3(0.0f, 0.0f, -1.0f), glm::normalize(glm::vec3(0.3f, 0.8f, -1.0f)),
                            glm::normalize(glm::vec3(-0.2f, -0.5f, 1.0f))}) {
            CAPTURE(origin.y);
            CAPTURE(w.y);
            const double d = 7.0;
            const double depthThere = integratedDepth(fog, origin, w, d);
            CHECK(opticalDepth(fog, origin, w, d) == doctest::Approx(depthThere).epsilon(1e-6));
            for (float u : {0.0f, 0.1f, 0.5f, 0.9f, 0.999f}) {
                CAPTURE(u);
                const float t = sampleDistance(fog, origin, w, d, u);
                REQUIRE(t >= 0.0f);
                REQUIRE(t <= d);
                CHECK(-std::expm1(-integratedDepth(fog, origin, w, t)) ==
                      doctest::Approx(u * -std::expm1(-depthThere)).epsilon(1e-5));
            }
        }
    // Upward to infinity: sigma_t(origin) / (falloff x w.y), plus the constant layer's share from
    // below; downward forever: opaque.
    const glm::vec3 up = glm::normalize(glm::vec3(0.3f, 0.8f, -1.0f)), high(0.0f, 2.0f, 0.0f),
                    low(0.0f, 0.2f, 0.0f);
    const double inf = std::numeric_limits<double>::infinity();
    CHECK(extinction(fog, high) == doctest::Approx(0.3 * std::exp(-0.7)).epsilon(1e-6));
    CHECK(extinction(fog, low) == doctest::Approx(0.3).epsilon(1e-6));
    CHECK(opticalDepth(fog, high, up, inf) ==
          doctest::Approx(0.3 * std::exp(-0.7) / (0.7 * up.y)).epsilon(1e-6));
    CHECK(opticalDepth(fog, low, up, inf) ==
          doctest::Approx(0.3 * 0.8 / up.y + 0.3 / (0.7 * up.y)).epsilon(1e-6));
    CHECK(transmittance(fog, high, -up, inf) == 0.0f);
}

TEST_CASE("reference: the sun's single scattering in a homogeneous medium") {
    const float depth = 5.0f, sigma = 0.2f;
    engine::Scene scene = wallAt(depth);
    const glm::vec3 e(3.0f, 2.0f, 1.0f);
    // Travelling along the wall and slightly toward it, so that the wall never shadows the medium.
    scene.lights.push_back(sunLight({-1.0f, 0.0f, -0.2f}, e));
    const RayScene rays(scene);
    const SceneLights lights(scene);
    const glm::vec3 sunDirection = scene.lights[0].direction;
    Medium medium;
    medium.density = sigma;
    medium.albedo = {0.9f, 0.8f, 0.7f};
    for (float g : {0.0f, 0.6f}) {
        medium.anisotropy = g;
        for (float angle : {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f}) {
            CAPTURE(g);
            CAPTURE(angle);
            const glm::vec3 w(std::sin(angle), 0.0f, -std::cos(angle));
            const double d = depth / std::cos(double(angle));
            const MediumRadiance r = scatteredAlongRay(rays, lights, medium, glm::vec3(0.0f), w, 0, 8, 1);
            // sigma_s E p(cos) (1 - exp(-sigma_t d)) / sigma_t, cos between the sun's and the view's
            // directions of travel.
            const double phase = henyeyGreenstein(glm::dot(sunDirection, -w), g);
            for (int c = 0; c < 3; ++c)
                CHECK(
                    r.sun[c] ==
                    doctest::Approx(medium.albedo[c] * e[c] * phase * -std::expm1(-sigma * d)).epsilon(1e-5));
            CHECK(r.indirect == glm::vec3(0.0f)); // no bounces asked for
        }
    }
    const glm::vec3 w(std::sin(0.5f), 0.0f, -std::cos(0.5f));
    const double expected = 0.9 * 3.0 * henyeyGreenstein(glm::dot(sunDirection, -w), 0.6f) *
                            -std::expm1(-sigma * depth / std::cos(0.5));
    std::printf("sun in fog, g = 0.6, 0.5 rad off the wall's normal: in-scatter %.6f, expected %.6f\n",
                scatteredAlongRay(rays, lights, medium, glm::vec3(0.0f), w, 0, 8, 1).sun.r, expected);
}

TEST_CASE("reference: the sun's single scattering is shadowed by the scene, and optionally by the fog") {
    const float depth = 4.0f, sigma = 0.25f, e = 2.0f;
    engine::Scene scene = wallAt(depth);
    scene.lights.push_back(sunLight({0.0f, -1.0f, 0.0f}, glm::vec3(e)));
    // A roof over the far half of the ray z = 0 .. -depth at y = 0.
    engine::MeshBuilder builder(scene);
    builder.begin("roof", 0);
    builder.quad({-50.0f, 1.0f, -depth}, {100.0f, 0.0f, 0.0f}, {0.0f, 0.0f, depth / 2.0f});
    builder.finish();
    const RayScene rays(scene);
    const SceneLights lights(scene);
    Medium medium;
    medium.density = sigma;
    medium.albedo = glm::vec3(1.0f);
    medium.anisotropy = 0.0f;
    const glm::vec3 w(0.0f, 0.0f, -1.0f);
    const double weight = e * henyeyGreenstein(0.0f, 0.0f);
    // Only the near half is lit. Of N strata one straddles the shadow's edge: an error of at most
    // one sample's weight, e p (1 - T(d)) / N.
    constexpr uint32_t kSamples = 2048;
    const MediumRadiance r = scatteredAlongRay(rays, lights, medium, glm::vec3(0.0f), w, 0, kSamples, 1);
    const double expected = weight * -std::expm1(-sigma * depth / 2.0);
    CHECK(std::abs(r.sun.r - expected) <= weight * -std::expm1(-sigma * depth) / kSamples + 1e-5 * expected);
    std::printf("sun in fog, half shadowed: %.6f, expected %.6f\n", r.sun.r, expected);

    // Height fog, seen level at y = 1 under the sun overhead (no roof): with attenuateSunlight the
    // sun arrives through optical depth sigma_t(y) / falloff above the ray.
    engine::Scene open = wallAt(depth);
    open.lights = scene.lights;
    const RayScene openRays(open);
    const SceneLights openLights(open);
    Medium fog = medium;
    fog.density = 0.4f;
    fog.heightFalloff = 0.5f;
    fog.baseHeight = -1.0f;
    const glm::vec3 origin(0.0f, 1.0f, 0.0f);
    const double sigmaThere = 0.4 * std::exp(-0.5 * 2.0);
    const double unattenuated = weight * -std::expm1(-sigmaThere * depth);
    CHECK(scatteredAlongRay(openRays, openLights, fog, origin, w, 0, 4, 1).sun.r ==
          doctest::Approx(unattenuated).epsilon(1e-5));
    fog.attenuateSunlight = true;
    CHECK(scatteredAlongRay(openRays, openLights, fog, origin, w, 0, 4, 1).sun.r ==
          doctest::Approx(unattenuated * std::exp(-sigmaThere / 0.5)).epsilon(1e-5));
    fog.heightFalloff = 0.0f; // homogeneous and endless above: the sun is gone
    CHECK(scatteredAlongRay(openRays, openLights, fog, origin, w, 0, 4, 1).sun.r == 0.0f);
}

TEST_CASE("reference: fog in a uniform radiance field scatters albedo x L x (1 - T)") {
    // A closed box of albedo a under uniform irradiance E0: every wall leaves L = a E0 / pi, and
    // a E0 (1 + a) / pi with a second bounce (the furnace), from every direction.
    const float a = 0.5f, e0 = 2.0f;
    engine::Scene scene = sceneWith(glm::vec3(a));
    engine::MeshBuilder builder(scene);
    builder.begin("box", 0);
    const glm::vec3 lo(-2.0f, -1.0f, -3.0f), hi(3.0f, 2.0f, 1.0f);
    builder.box(lo, hi, true);
    builder.finish();
    const RayScene rays(scene, RayScene::Surfaces::Lambertian);
    const UniformIrradiance source{glm::vec3(e0)};
    Medium medium;
    medium.density = 0.3f;
    medium.albedo = {0.9f, 0.6f, 0.3f};
    medium.anisotropy = 0.6f;
    const glm::vec3 origin(0.1f, 0.2f, 0.3f);
    for (uint32_t bounces = 1; bounces <= 2; ++bounces) {
        const double radiance = a * e0 / kPi * (bounces == 2 ? 1.0 + a : 1.0);
        for (glm::vec3 w : {glm::vec3(0.0f, 0.0f, -1.0f), glm::normalize(glm::vec3(0.7f, 0.3f, 0.2f)),
                            glm::normalize(glm::vec3(-0.2f, -0.9f, 0.4f))}) {
            CAPTURE(bounces);
            CAPTURE(w.x);
            // The box's exit distance along w.
            double d = std::numeric_limits<double>::infinity();
            for (int c = 0; c < 3; ++c)
                if (w[c] != 0.0f) d = std::min(d, double(((w[c] > 0.0f ? hi[c] : lo[c]) - origin[c]) / w[c]));
            const MediumRadiance r = scatteredAlongRay(rays, source, medium, origin, w, bounces, 16, 3);
            CHECK(r.distance == doctest::Approx(d).epsilon(1e-5));
            for (int c = 0; c < 3; ++c)
                CHECK(r.indirect[c] ==
                      doctest::Approx(medium.albedo[c] * radiance * -std::expm1(-0.3 * d)).epsilon(1e-5));
            CHECK(r.sun == glm::vec3(0.0f));
        }
    }

    // The same per pixel: fog_indirect = albedo L (1 - transmittance), and the camera sees the walls'
    // uniform radiance through the fog: fogged = combined x transmittance + fog.
    medium.heightFalloff = 0.4f;
    TraceSettings settings;
    settings.width = settings.height = 12;
    settings.samplesPerPixel = 4;
    settings.medium = medium;
    settings.mediumSamples = 2;
    const TracedImage image = trace(rays, source, lookingAt(origin, {1.0f, -0.5f, -2.0f}, 100.0f), settings);
    const double radiance = a * e0 / kPi;
    for (size_t i = 0; i < image.fog.size(); ++i) {
        CAPTURE(i);
        const double t = image.transmittance[i].r;
        REQUIRE(t > 0.0);
        REQUIRE(t < 1.0);
        for (int c = 0; c < 3; ++c) {
            CHECK(image.fogIndirect[i][c] ==
                  doctest::Approx(medium.albedo[c] * radiance * (1.0 - t)).epsilon(1e-5));
            CHECK(image.fogged[i][c] ==
                  doctest::Approx(image.combined[i][c] * t + image.fog[i][c]).epsilon(1e-5));
        }
        CHECK(image.fogSun[i] == glm::vec3(0.0f));
    }
}

TEST_CASE("reference: fog before a lit wall scatters its light by the phase function's lobe") {
    // A wall wide enough to fill the half space beyond it, leaving L = a E0 / pi. Looking straight at
    // it, the light it sends travels toward the camera's side: the share of the phase function
    // scattering it toward the camera is P(cos > 0), large forward (g > 0), small backward.
    const float a = 0.5f, e0 = 2.0f, depth = 3.0f, sigma = 0.3f;
    engine::Scene scene = sceneWith(glm::vec3(a));
    engine::MeshBuilder builder(scene);
    builder.begin("wall", 0);
    builder.quad({-1e4f, -1e4f, -depth}, {2e4f, 0.0f, 0.0f}, {0.0f, 2e4f, 0.0f});
    builder.finish();
    const RayScene rays(scene, RayScene::Surfaces::Lambertian);
    const UniformIrradiance source{glm::vec3(e0)};
    Medium medium;
    medium.density = sigma;
    medium.albedo = glm::vec3(1.0f);
    constexpr uint32_t kSamples = 4096;
    for (float g : {0.6f, -0.6f}) {
        CAPTURE(g);
        medium.anisotropy = g;
        const double share = 1.0 - henyeyGreensteinCdf(0.0, g);
        const MediumRadiance r =
            scatteredAlongRay(rays, source, medium, glm::vec3(0.0f), {0.0f, 0.0f, -1.0f}, 1, kSamples, 5);
        // Each sample sees the wall or not: a binomial estimate of the share, to 5 standard errors.
        const double scale = a * e0 / kPi * -std::expm1(-sigma * depth);
        CHECK(std::abs(r.indirect.g / scale - share) < 5.0 * std::sqrt(share * (1.0 - share) / kSamples));
        std::printf("fog before a lit wall, g = %+.1f: share seen %.4f, P(cos > 0) %.4f\n", g,
                    r.indirect.g / scale, share);
    }
}

TEST_CASE("reference: fog of zero density changes nothing, and fog leaves the surfaces' images alone") {
    const engine::Scene scene = engine::loadScene("cornell");
    const engine::Camera camera = engine::defaultCamera(scene);
    TraceSettings settings;
    settings.width = settings.height = 24;
    settings.samplesPerPixel = 4;
    settings.bounces = 2;
    const TracedImage plain = trace(scene, camera, settings);
    settings.medium.albedo = glm::vec3(0.5f);
    settings.medium.anisotropy = 0.5f;
    settings.medium.heightFalloff = 0.3f;
    settings.mediumSamples = 3;
    const TracedImage zero = trace(scene, camera, settings);
    settings.medium.density = 0.2f;
    const TracedImage foggy = trace(scene, camera, settings);
    for (const TracedImage* image : {&zero, &foggy}) {
        CHECK(image->direct == plain.direct);
        CHECK(image->indirect == plain.indirect);
        CHECK(image->combined == plain.combined);
        CHECK(image->position == plain.position);
        CHECK(image->normal == plain.normal);
        CHECK(image->hit == plain.hit);
    }
    for (const TracedImage* image : {&plain, &zero}) {
        CHECK(image->fogged == plain.combined);
        for (size_t i = 0; i < image->fog.size(); ++i) {
            REQUIRE(image->fog[i] == glm::vec3(0.0f));
            REQUIRE(image->fogSun[i] == glm::vec3(0.0f));
            REQUIRE(image->fogIndirect[i] == glm::vec3(0.0f));
            REQUIRE(image->transmittance[i] == glm::vec3(1.0f));
        }
    }
    double sun = 0.0, indirect = 0.0;
    for (size_t i = 0; i < foggy.fog.size(); ++i) {
        CHECK(foggy.fog[i] == foggy.fogSun[i] + foggy.fogIndirect[i]);
        CHECK(foggy.transmittance[i].r < 1.0f);
        CHECK(foggy.transmittance[i].r > 0.0f);
        sun += foggy.fogSun[i].r;
        indirect += foggy.fogIndirect[i].r;
    }
    CHECK(sun > 0.0);
    CHECK(indirect > 0.0);
}
