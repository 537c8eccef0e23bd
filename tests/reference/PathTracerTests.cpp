// The path-traced reference against closed forms: a white furnace (the geometric series per
// bounce), the form factor of two parallel squares, the sun's and the punctual lights' direct
// terms (exact), determinism across thread counts, and PFM round trips.
//
// Noise and bounds: the furnace is noise-free (every path in a closed box of one albedo under a
// uniform source carries the same value), and so are the direct terms (no sampling in them). The
// form factor is a Bernoulli estimate per path: a ray from the receiver hits the emitter with
// probability F ~ 0.2, so one path's relative standard deviation is sqrt((1 - F) / F) = 2.0; with
// 32 x 32 points x 512 paths (524288 paths) the standard error is 2.0 / 724 = 0.28%, and the 1%
// bound is 3.6 standard errors (the points are cell centres, whose quadrature error is ~1e-4).
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
#include <optional>
#include <string>

using namespace lpv;
using namespace lpv::reference;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Every surface (or only one instance's) receives the same direct irradiance: a light source with a
// known answer, standing in for SceneLights.
class UniformIrradiance : public DirectLighting {
public:
    explicit UniformIrradiance(glm::vec3 e, int32_t onlyInstance = -1) : e_(e), only_(onlyInstance) {}
    glm::vec3 irradiance(const SurfacePoint& p, const RayScene&) const override {
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
    const RayScene rays(scene);
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
    const RayScene rays(scene);
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
            sum += indirectIrradiance(rays, source, p, 1, kPaths, j * kGrid + i).g;
        }
    const double f = sum / (kGrid * kGrid) / (a * e0);
    const double expected = parallelRectangles(1.0, 1.0, 1.0);
    std::printf("parallel unit squares at distance 1: F = %.5f, closed form %.5f\n", f, expected);
    CHECK(expected == doctest::Approx(0.19982).epsilon(1e-4));
    CHECK(f == doctest::Approx(expected).epsilon(0.01));
}

TEST_CASE("reference: the sun's direct term on a floor is albedo x E x cos / pi") {
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
    const TracedImage image =
        trace(scene, lookingAt({0.0f, 2.0f, 1.0f}, {0.0f, 0.0f, -1.0f}, 60.0f), settings);
    const glm::vec3 expected = albedo * sun.color * sun.intensity * -sun.direction.y / float(kPi);
    for (size_t i = 0; i < image.direct.size(); ++i) {
        REQUIRE(image.hit[i] == 1);
        for (int c = 0; c < 3; ++c) {
            CHECK(image.direct[i][c] == doctest::Approx(expected[c]).epsilon(1e-5));
            CHECK(image.indirect[i][c] == 0.0f); // nothing else to bounce off
            CHECK(image.combined[i][c] == image.direct[i][c]);
        }
        CHECK(image.normal[i].y == doctest::Approx(1.0f));
        CHECK(image.position[i].y == doctest::Approx(0.0f));
    }
    std::printf("sun on a floor: direct %.6f (red), expected %.6f\n", image.direct[0].r, expected.r);
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
        CHECK(lights.irradiance(at(p), rays).r == doctest::Approx(expected).epsilon(1e-5));
        CHECK(lights.irradiance(at(p), rays).b == doctest::Approx(0.25f * expected).epsilon(1e-5));
        // Beyond the range window, and below the blocker's shadow.
        CHECK(lights.irradiance(at({6.5f, 0.0f, 0.0f}), rays).r == 0.0f);
        CHECK(lights.irradiance(at({5.0f, 1e-3f, 0.0f}), rays).r > 0.0f);
        lit.lights[0].position = {5.0f, 2.0f, 0.0f};
        const SceneLights above(lit);
        CHECK(above.irradiance(at({5.0f, 0.0f, 0.0f}), rays).r == 0.0f);
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
            CHECK(lights.irradiance(at(p), rays).r == doctest::Approx(expected).epsilon(1e-5));
        }
    }
}

TEST_CASE("reference: albedo is base colour factor x sRGB texture x (1 - metallic)") {
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
    settings.threads = 1;
    const TracedImage one = trace(scene, camera, settings);
    settings.threads = 2;
    const TracedImage two = trace(scene, camera, settings);
    CHECK(one.indirect == two.indirect);
    CHECK(one.direct == two.direct);
    CHECK(one.hit == two.hit);
    settings.seed = 2;
    const TracedImage other = trace(scene, camera, settings);
    CHECK(other.indirect != one.indirect);
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
