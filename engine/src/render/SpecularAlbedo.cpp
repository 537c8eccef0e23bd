#include "engine/render/SpecularAlbedo.h"

#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lpv::engine {
namespace {

// The base-2 radical inverse of i (its bits mirrored behind the binary point): with i / n it
// spreads n points evenly over the unit square (the Hammersley set).
float radicalInverse(uint32_t i) {
    uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 0x1p-32f;
}

} // namespace

SpecularAlbedo integrateSpecularAlbedo(float cosView, float roughness, uint32_t samples) {
    // A perfect mirror is a delta lobe: kept just off it so the sampling below stays finite.
    const float alpha = std::max(roughness * roughness, 1e-3f);
    const float a2 = alpha * alpha, k = alpha / 2.0f;
    const float nv = std::clamp(cosView, 1e-4f, 1.0f);
    // The view in the tangent frame (normal along z, view in the xz plane).
    const float vx = std::sqrt(1.0f - nv * nv), vz = nv;
    double scale = 0.0, bias = 0.0;
    glm::dvec2 scaleDirection(0.0), biasDirection(0.0);
    for (uint32_t i = 0; i < samples; ++i) {
        // A half vector distributed as D(h) (h . n): the inverse of GGX's cumulative distribution.
        const float u = (float(i) + 0.5f) / float(samples),
                    phi = 2.0f * std::numbers::pi_v<float> * radicalInverse(i);
        const float cosH = std::sqrt((1.0f - u) / (1.0f + (a2 - 1.0f) * u));
        const float sinH = std::sqrt(std::max(1.0f - cosH * cosH, 0.0f));
        const float hx = sinH * std::cos(phi), hz = cosH;
        const float vh = vx * hx + vz * hz;
        const float nl = 2.0f * vh * hz - vz; // the light's z: the view mirrored about h
        if (nl <= 0.0f || vh <= 0.0f) continue;
        // The estimator of f cos(l) / pdf for this pdf is G (v.h) / ((n.h)(n.v)); G's view half
        // cancels the 1 / (n.v), which keeps grazing views finite.
        const float maskLight = nl / (nl * (1.0f - k) + k);
        const float weight = maskLight * vh / (hz * (nv * (1.0f - k) + k));
        const float fresnel = std::pow(1.0f - vh, 5.0f);
        scale += double((1.0f - fresnel) * weight);
        bias += double(fresnel * weight);
        // The light along n and toward the mirror direction (-x here); its part along y (the
        // half vector's azimuth) cancels between the mirrored samples of the lobe.
        const glm::dvec2 l(nl, -(2.0f * vh * hx - vx));
        scaleDirection += double((1.0f - fresnel) * weight) * l;
        biasDirection += double(fresnel * weight) * l;
    }
    const double n = double(samples);
    return {float(scale / n), float(bias / n), glm::vec2(scaleDirection / n), glm::vec2(biasDirection / n)};
}

float integrateSchlickMean(float cosLight, uint32_t steps) {
    // The light in the xz plane; the views over the hemisphere by (theta, phi), dw = sin d(theta) d(phi).
    const double nl = std::clamp(double(cosLight), 0.0, 1.0), lx = std::sqrt(1.0 - nl * nl);
    const double dTheta = std::numbers::pi / 2.0 / steps, dPhi = std::numbers::pi / steps;
    double sum = 0.0;
    for (uint32_t t = 0; t < steps; ++t) {
        const double theta = (t + 0.5) * dTheta, vz = std::cos(theta), sinV = std::sin(theta);
        for (uint32_t p = 0; p < 2 * steps; ++p) {
            const double phi = (p + 0.5) * dPhi, vx = sinV * std::cos(phi), vy = sinV * std::sin(phi);
            const double hx = vx + lx, hy = vy, hz = vz + nl;
            const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
            const double vh = len > 0.0 ? (vx * hx + vy * hy + vz * hz) / len : 0.0;
            // cos(view) / pi is the weight of a view in the cosine-weighted mean.
            sum += std::pow(1.0 - std::clamp(vh, 0.0, 1.0), 5.0) * vz * sinV * dTheta * dPhi;
        }
    }
    return float(sum / std::numbers::pi);
}

float SpecularAlbedoTable::schlickMeanAt(float cosLight) const {
    const float x = std::clamp(cosLight, 0.0f, 1.0f) * float(kSize - 1);
    const uint32_t i = std::min(uint32_t(x), kSize - 2);
    return schlickMean[i] + (schlickMean[i + 1] - schlickMean[i]) * (x - float(i));
}

SpecularAlbedo SpecularAlbedoTable::at(float cosView, float roughness) const {
    const float last = float(kSize - 1);
    const float x = std::clamp(cosView, 0.0f, 1.0f) * last, y = std::clamp(roughness, 0.0f, 1.0f) * last;
    const uint32_t x0 = std::min(uint32_t(x), kSize - 2), y0 = std::min(uint32_t(y), kSize - 2);
    const float fx = x - float(x0), fy = y - float(y0);
    const auto texel = [&](uint32_t i, uint32_t j) { return texels[j * kSize + i]; };
    const auto lerp = [](SpecularAlbedo a, SpecularAlbedo b, float t) {
        return SpecularAlbedo{a.scale + (b.scale - a.scale) * t, a.bias + (b.bias - a.bias) * t,
                              a.scaleDirection + (b.scaleDirection - a.scaleDirection) * t,
                              a.biasDirection + (b.biasDirection - a.biasDirection) * t};
    };
    return lerp(lerp(texel(x0, y0), texel(x0 + 1, y0), fx),
                lerp(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), fx), fy);
}

const SpecularAlbedoTable& specularAlbedoTable() {
    static const SpecularAlbedoTable table = [] {
        SpecularAlbedoTable t;
        t.texels.resize(size_t(SpecularAlbedoTable::kSize) * SpecularAlbedoTable::kSize);
        const float last = float(SpecularAlbedoTable::kSize - 1);
        for (uint32_t j = 0; j < SpecularAlbedoTable::kSize; ++j)
            for (uint32_t i = 0; i < SpecularAlbedoTable::kSize; ++i)
                t.texels[j * SpecularAlbedoTable::kSize + i] =
                    integrateSpecularAlbedo(float(i) / last, float(j) / last, SpecularAlbedoTable::kSamples);
        for (uint32_t i = 0; i < SpecularAlbedoTable::kSize; ++i)
            t.schlickMean[i] = integrateSchlickMean(float(i) / last, 64);
        return t;
    }();
    return table;
}

} // namespace lpv::engine
