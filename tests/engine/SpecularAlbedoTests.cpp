// The glossy term's weight (engine/render/SpecularAlbedo.h): the importance-sampled integral agrees
// with a plain quadrature of the same BRDF over the hemisphere, a mirror reflects all it receives
// with Schlick's Fresnel, no texel reflects more than arrives, and roughness takes away the grazing
// gain that Schlick's Fresnel alone gives. The Schlick mean (the share of a light fresnel_mix takes
// from the diffuse base over all views) agrees with a random sampling of the views.
#include "engine/render/SpecularAlbedo.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

using namespace lpv::engine;

namespace {

// The integral of f cos(l) over the hemisphere on a grid of light directions (midpoint rule in
// cos(theta) and phi), f the GGX / Smith-Schlick / Schlick BRDF written out: a different method
// from the sampling under test, sharing only the model.
SpecularAlbedo hemisphereQuadrature(float cosView, float roughness) {
    const double alpha = double(roughness) * roughness, a2 = alpha * alpha, k = alpha / 2.0;
    const double nv = cosView, vx = std::sqrt(1.0 - nv * nv);
    const int thetaSteps = 1024, phiSteps = 1024;
    double scale = 0.0, bias = 0.0;
    for (int t = 0; t < thetaSteps; ++t) {
        const double nl = (t + 0.5) / thetaSteps, sinL = std::sqrt(1.0 - nl * nl);
        for (int p = 0; p < phiSteps; ++p) {
            const double phi = 2.0 * std::numbers::pi * (p + 0.5) / phiSteps;
            const double lx = sinL * std::cos(phi), ly = sinL * std::sin(phi);
            double hx = lx + vx, hy = ly, hz = nl + nv;
            const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
            hx /= len;
            hy /= len;
            hz /= len;
            const double vh = vx * hx + nv * hz;
            const double denom = hz * hz * (a2 - 1.0) + 1.0;
            const double d = a2 / (std::numbers::pi * denom * denom);
            const double g = nl / (nl * (1.0 - k) + k) * nv / (nv * (1.0 - k) + k);
            const double fresnel = std::pow(1.0 - vh, 5.0);
            // f cos(l) dw with dw = d(cos) d(phi).
            const double common =
                d * g / (4.0 * nl * nv) * nl * (1.0 / thetaSteps) * (2.0 * std::numbers::pi / phiSteps);
            scale += common * (1.0 - fresnel);
            bias += common * fresnel;
        }
    }
    return {float(scale), float(bias)};
}

float weight(SpecularAlbedo s, float f0) {
    return f0 * s.scale + s.bias;
}

} // namespace

TEST_CASE("specular albedo: importance sampling agrees with a quadrature over the hemisphere") {
    // Roughness from 0.3 up: smoother lobes are too narrow for a 1024^2 grid.
    for (const float roughness : {0.3f, 0.5f, 0.8f, 1.0f})
        for (const float cosView : {0.15f, 0.5f, 0.9f}) {
            const SpecularAlbedo sampled = integrateSpecularAlbedo(cosView, roughness, 4096);
            const SpecularAlbedo grid = hemisphereQuadrature(cosView, roughness);
            INFO("roughness " << roughness << ", cos(view) " << cosView << ": sampled " << sampled.scale
                              << " / " << sampled.bias << ", quadrature " << grid.scale << " / "
                              << grid.bias);
            CHECK(sampled.scale == doctest::Approx(grid.scale).epsilon(0.01));
            CHECK(sampled.bias == doctest::Approx(grid.bias).epsilon(0.02).scale(0.01));
        }
}

TEST_CASE("specular albedo: a mirror reflects all of the light, with Schlick's Fresnel") {
    const SpecularAlbedoTable& table = specularAlbedoTable();
    for (const float cosView : {0.2f, 0.5f, 1.0f}) {
        const SpecularAlbedo s = table.at(cosView, 0.0f);
        const float schlick = 0.04f + 0.96f * std::pow(1.0f - cosView, 5.0f);
        INFO("cos(view) " << cosView << ": scale " << s.scale << ", bias " << s.bias);
        CHECK(weight(s, 1.0f) == doctest::Approx(1.0f).epsilon(0.01));     // a metal of albedo 1
        CHECK(weight(s, 0.04f) == doctest::Approx(schlick).epsilon(0.03)); // a dielectric
    }
}

TEST_CASE(
    "specular albedo: no surface reflects more than it receives, and roughness takes the grazing gain") {
    const SpecularAlbedoTable& table = specularAlbedoTable();
    REQUIRE(table.texels.size() == size_t(SpecularAlbedoTable::kSize) * SpecularAlbedoTable::kSize);
    for (const SpecularAlbedo& s : table.texels) {
        CHECK(s.scale >= 0.0f);
        CHECK(s.bias >= 0.0f);
        CHECK(weight(s, 1.0f) <= 1.0f + 1e-3f);
    }
    // At a grazing view (cos 0.1) the Fresnel gain falls as the lobe widens: more of it is masked.
    float previous = 2.0f;
    for (const float roughness : {0.2f, 0.4f, 0.6f, 0.8f, 1.0f}) {
        const float bias = table.at(0.1f, roughness).bias;
        INFO("roughness " << roughness << ": bias " << bias);
        CHECK(bias < previous);
        previous = bias;
    }
    // The atrium's stone (roughness 0.7, F0 4%) seen at cos 0.1: Schlick's Fresnel alone gives 0.61,
    // the former weight (Schlick x (1 - roughness)) 0.18; the lobe reflects well under a tenth.
    CHECK(weight(table.at(0.1f, 0.7f), 0.04f) < 0.1f);
}

TEST_CASE("specular albedo: the Schlick mean agrees with random views and grows toward grazing light") {
    // Views drawn uniformly over the hemisphere (pdf 1 / 2 pi), each weighted by cos(view) / pi.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const SpecularAlbedoTable& table = specularAlbedoTable();
    float previous = -1.0f;
    for (const float cosLight : {1.0f, 0.7f, 0.4f, 0.15f, 0.0f}) {
        const double lx = std::sqrt(1.0 - double(cosLight) * cosLight);
        const int samples = 400000;
        double sum = 0.0;
        for (int i = 0; i < samples; ++i) {
            const double vz = uniform(random), phi = 2.0 * std::numbers::pi * uniform(random);
            const double r = std::sqrt(1.0 - vz * vz), vx = r * std::cos(phi), vy = r * std::sin(phi);
            const double hx = vx + lx, hy = vy, hz = vz + cosLight;
            const double vh = (vx * hx + vy * hy + vz * hz) / std::sqrt(hx * hx + hy * hy + hz * hz);
            sum += std::pow(1.0 - vh, 5.0) * vz / std::numbers::pi * 2.0 * std::numbers::pi;
        }
        const float sampled = float(sum / samples), mean = table.schlickMeanAt(cosLight);
        INFO("cos(light) " << cosLight << ": table " << mean << ", random views " << sampled);
        CHECK(mean == doctest::Approx(sampled).epsilon(0.03).scale(1e-3));
        CHECK(mean > previous); // more of the light is taken the more grazing it arrives
        previous = mean;
    }
    // Light along the normal loses almost nothing beyond F0; grazing light under 3%.
    CHECK(table.schlickMeanAt(1.0f) < 1e-4f);
    CHECK(table.schlickMeanAt(0.0f) < 0.03f);
}
