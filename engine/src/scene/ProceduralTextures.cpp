// Texture generators for the atrium. Patterns are functions of (u, v) in [0, 1); noise is a
// fixed-seed integer hash on a lattice that wraps at the image edge, so every image tiles.
#include "ProceduralTextures.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace lpv::engine::textures {
namespace {

uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
    // Integer mixing after Chris Wellons' "lowbias32"; enough for texture grain, no state.
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ (seed + 1u) * 0xcb1ab31fu;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    h ^= h >> 16;
    return h;
}

float hash01(uint32_t x, uint32_t y, uint32_t seed) {
    return float(hash(x, y, seed) >> 8) * (1.0f / 16777216.0f);
}

// Smooth value noise in [0, 1] with `period` lattice cells across [0, 1), periodic in u and v.
float valueNoise(float u, float v, uint32_t period, uint32_t seed) {
    const float x = u * float(period), y = v * float(period);
    const float fx = std::floor(x), fy = std::floor(y);
    const auto wrap = [period](float c) {
        const int64_t p = int64_t(period), i = int64_t(c) % p;
        return uint32_t(i < 0 ? i + p : i);
    };
    const uint32_t x0 = wrap(fx), x1 = wrap(fx + 1.0f), y0 = wrap(fy), y1 = wrap(fy + 1.0f);
    float tx = x - fx, ty = y - fy;
    tx = tx * tx * (3.0f - 2.0f * tx);
    ty = ty * ty * (3.0f - 2.0f * ty);
    const float a = glm::mix(hash01(x0, y0, seed), hash01(x1, y0, seed), tx);
    const float b = glm::mix(hash01(x0, y1, seed), hash01(x1, y1, seed), tx);
    return glm::mix(a, b, ty);
}

// Fractal sum of `octaves` value noises, each twice the frequency of the last; in [0, 1].
float fbm(float u, float v, uint32_t period, int octaves, uint32_t seed) {
    float sum = 0.0f, amplitude = 1.0f, norm = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * valueNoise(u, v, period << o, seed + uint32_t(o) * 7919u);
        norm += amplitude;
        amplitude *= 0.5f;
    }
    return sum / norm;
}

uint8_t toByte(float c) {
    return uint8_t(std::lround(glm::clamp(c, 0.0f, 1.0f) * 255.0f));
}

// Fills an image from `color(u, v)` sampled at texel centres; colours are in the image's space
// (sRGB for albedo, which is also how the constants below were picked).
template <class ColorFn>
TextureImage makeImage(std::string name, uint32_t width, uint32_t height, bool srgb, ColorFn&& color) {
    TextureImage img;
    img.name = std::move(name);
    img.width = width;
    img.height = height;
    img.srgb = srgb;
    img.rgba.resize(size_t(width) * height * 4);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const glm::vec3 c = color((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
            uint8_t* p = &img.rgba[(size_t(y) * width + x) * 4];
            p[0] = toByte(c.r);
            p[1] = toByte(c.g);
            p[2] = toByte(c.b);
            p[3] = 255;
        }
    return img;
}

// A tangent-space normal map from a height field given in metres over an image `extent` metres
// wide. Green follows +v (growing row index): MeshBuilder's bitangent cross(N, T) * w points along
// +v, as glTF renderers reconstruct it.
template <class HeightFn>
TextureImage normalMapFromHeight(std::string name, uint32_t size, float extent, HeightFn&& height) {
    std::vector<float> h(size_t(size) * size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
            h[size_t(y) * size + x] =
                height((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
    const float texel = extent / float(size);
    const auto at = [&](uint32_t x, uint32_t y) { return h[size_t(y % size) * size + x % size]; };
    TextureImage img;
    img.name = std::move(name);
    img.width = img.height = size;
    img.srgb = false;
    img.rgba.resize(size_t(size) * size * 4);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const float dx = (at(x + 1, y) - at(x + size - 1, y)) / (2.0f * texel);
            const float dy = (at(x, y + 1) - at(x, y + size - 1)) / (2.0f * texel);
            const glm::vec3 n = glm::normalize(glm::vec3(-dx, -dy, 1.0f));
            uint8_t* p = &img.rgba[(size_t(y) * size + x) * 4];
            p[0] = toByte(n.x * 0.5f + 0.5f);
            p[1] = toByte(n.y * 0.5f + 0.5f);
            p[2] = toByte(n.z * 0.5f + 0.5f);
            p[3] = 255;
        }
    return img;
}

// --- Floor tiles: 2 x 2 tiles of 0.5 m per image (the image spans 1 m) -------------------------

constexpr float kTileSize = 0.5f, kGroutHalfWidth = 0.0025f, kTileBevel = 0.004f;

struct TileCell {
    uint32_t ix, iy;
    float edgeDistance; // metres from the tile's nearest edge
};

TileCell tileAt(float u, float v) {
    const float x = u / kTileSize, y = v / kTileSize;
    const float fx = x - std::floor(x), fy = y - std::floor(y);
    const float edge = std::min(std::min(fx, 1.0f - fx), std::min(fy, 1.0f - fy)) * kTileSize;
    return {uint32_t(x), uint32_t(y), edge};
}

// --- Bricks: 0.25 m x 0.0625 m courses in running bond (the image spans 1 m) -----------------------

constexpr uint32_t kBricksAcross = 4, kCourses = 16;
constexpr float kMortarHalfWidth = 0.005f, kBrickBevel = 0.004f;

struct BrickCell {
    uint32_t column, course;
    float edgeDistance; // metres from the brick's nearest edge
};

BrickCell brickAt(float u, float v) {
    const float y = v * float(kCourses);
    const uint32_t course = uint32_t(y);
    const float x = u * float(kBricksAcross) + (course % 2 ? 0.5f : 0.0f);
    const float fx = x - std::floor(x), fy = y - std::floor(y);
    const float edge =
        std::min(std::min(fx, 1.0f - fx) / float(kBricksAcross), std::min(fy, 1.0f - fy) / float(kCourses));
    return {uint32_t(x) % kBricksAcross, course, edge};
}

} // namespace

TextureImage stoneAlbedo(uint32_t size) {
    return makeImage("stone", size, size, true, [](float u, float v) {
        const float mottle = fbm(u, v, 4, 5, 11);
        const float pits = glm::smoothstep(0.62f, 0.75f, fbm(u, v, 32, 2, 12));
        const float tint = fbm(u, v, 2, 2, 13);
        const glm::vec3 base = glm::mix(glm::vec3(0.80f, 0.74f, 0.63f), glm::vec3(0.74f, 0.71f, 0.66f), tint);
        return base * (0.82f + 0.3f * mottle) * (1.0f - 0.18f * pits);
    });
}

TextureImage plasterAlbedo(uint32_t size) {
    return makeImage("plaster", size, size, true, [](float u, float v) {
        const float stains = glm::smoothstep(0.45f, 0.8f, fbm(u, v, 2, 4, 21));
        const float grain = hash01(uint32_t(u * 4096.0f), uint32_t(v * 4096.0f), 22);
        return glm::vec3(0.88f, 0.85f, 0.80f) * (1.0f - 0.12f * stains) * (0.96f + 0.06f * grain);
    });
}

TextureImage floorTilesAlbedo(uint32_t size) {
    return makeImage("floor tiles", size, size, true, [](float u, float v) {
        const TileCell tile = tileAt(u, v);
        if (tile.edgeDistance < kGroutHalfWidth) return glm::vec3(0.42f, 0.40f, 0.37f);
        const bool dark = (tile.ix + tile.iy) % 2 == 1;
        // Marble: veins are the crests of a sine turbulently displaced by noise; the integer
        // frequencies along u and v keep it periodic.
        const uint32_t seed = dark ? 31u : 32u;
        const float turbulence = fbm(u, v, 4, 5, seed);
        const float phase = glm::two_pi<float>() * (3.0f * u + 2.0f * v) + 9.0f * turbulence;
        const float vein = std::pow(1.0f - std::fabs(std::sin(phase)), 10.0f);
        const float cloud = fbm(u, v, 8, 3, seed + 10u);
        const glm::vec3 base = dark ? glm::vec3(0.52f, 0.24f, 0.19f) : glm::vec3(0.90f, 0.86f, 0.78f);
        const glm::vec3 veinColor = dark ? glm::vec3(0.78f, 0.62f, 0.52f) : glm::vec3(0.55f, 0.52f, 0.50f);
        return glm::mix(base * (0.9f + 0.2f * cloud), veinColor, 0.7f * vein);
    });
}

TextureImage floorTilesNormal(uint32_t size) {
    return normalMapFromHeight("floor tiles normal", size, 1.0f, [](float u, float v) {
        // Grout lies 1.5 mm below the tile face, reached over a small bevel.
        const float e = tileAt(u, v).edgeDistance;
        return -0.0015f * (1.0f - glm::smoothstep(kGroutHalfWidth, kGroutHalfWidth + kTileBevel, e));
    });
}

TextureImage brickAlbedo(uint32_t size) {
    return makeImage("brick", size, size, true, [](float u, float v) {
        const BrickCell b = brickAt(u, v);
        const float grit = fbm(u, v, 64, 2, 41);
        if (b.edgeDistance < kMortarHalfWidth) return glm::vec3(0.68f, 0.66f, 0.60f) * (0.9f + 0.2f * grit);
        const float shade = hash01(b.column, b.course, 42), hue = hash01(b.column, b.course, 43);
        const glm::vec3 base = glm::mix(glm::vec3(0.60f, 0.28f, 0.19f), glm::vec3(0.66f, 0.40f, 0.26f), hue);
        const float burnt = hash01(b.column, b.course, 44) > 0.88f ? 0.65f : 1.0f;
        return base * (0.8f + 0.35f * shade) * burnt * (0.88f + 0.24f * grit);
    });
}

TextureImage brickNormal(uint32_t size) {
    return normalMapFromHeight("brick normal", size, 1.0f, [](float u, float v) {
        const BrickCell b = brickAt(u, v);
        const float face = 0.0008f * fbm(u, v, 32, 3, 45); // a rough, fired face
        const float edge = glm::smoothstep(kMortarHalfWidth, kMortarHalfWidth + kBrickBevel, b.edgeDistance);
        return glm::mix(-0.006f, face, edge);
    });
}

TextureImage woodAlbedo(uint32_t size) {
    constexpr uint32_t kPlanks = 6;
    return makeImage("wood", size, size, true, [](float u, float v) {
        const float y = v * float(kPlanks);
        const uint32_t plank = uint32_t(y);
        const float fy = y - std::floor(y);
        if (fy < 0.03f || fy > 0.97f) return glm::vec3(0.16f, 0.11f, 0.07f); // the gap between planks
        const float warp = fbm(u, v, 4, 4, 50 + plank);
        const float grain =
            0.5f + 0.5f * std::sin(glm::two_pi<float>() * (float(kPlanks * 7) * v + 3.0f * warp));
        const float tone = hash01(plank, 0, 51);
        const glm::vec3 base = glm::mix(glm::vec3(0.56f, 0.40f, 0.24f), glm::vec3(0.66f, 0.50f, 0.32f), tone);
        return base * (0.8f + 0.2f * grain);
    });
}

TextureImage bannerFabric(glm::vec3 fabric, glm::vec3 trim, uint32_t emblem, uint32_t width,
                          uint32_t height) {
    const float aspect = float(height) / float(width);
    return makeImage(
        "banner fabric " + std::to_string(emblem % 4), width, height, true, [&](float u, float v) {
            // Coordinates in banner widths, so shapes stay round whatever the banner's proportions.
            const float x = u - 0.5f, yTop = v * aspect;
            const float yFromBottom = (1.0f - v) * aspect;
            bool ornament = std::fabs(x) > 0.42f || yTop < 0.08f || yFromBottom < 0.08f; // border
            ornament =
                ornament || (std::fabs(std::fabs(x) - 0.37f) < 0.012f && yTop > 0.13f && yFromBottom > 0.13f);
            // The emblem, a third of the way down.
            const float ex = x, ey = yTop - 0.33f * aspect;
            const float r = std::sqrt(ex * ex + ey * ey), angle = std::atan2(ey, ex);
            switch (emblem % 4) {
            case 0:
                ornament = ornament || (r > 0.22f && r < 0.28f) || r < 0.09f;
                break;
            case 1:
                ornament = ornament || std::fabs(std::fabs(ex) + std::fabs(ey) - 0.26f) < 0.04f ||
                           std::fabs(ex) + std::fabs(ey) < 0.08f;
                break;
            case 2:
                ornament = ornament || (std::fabs(ex) < 0.06f && std::fabs(ey) < 0.28f) ||
                           (std::fabs(ey) < 0.06f && std::fabs(ex) < 0.28f);
                break;
            default:
                ornament = ornament || r < 0.12f || (r < 0.3f && std::cos(8.0f * angle) > 0.55f);
                break;
            }
            // A row of small diamonds above the bottom border.
            const float cell = x * 5.0f - std::floor(x * 5.0f) - 0.5f;
            ornament = ornament || (std::fabs(cell) * 0.2f + std::fabs(yFromBottom - 0.25f) < 0.06f);

            // Plain weave: warp and weft alternate on top every texel pair; the thread on top catches
            // more light, and a per-thread hash gives the uneven slubs of hand-woven cloth.
            const uint32_t tx = uint32_t(u * float(width)) / 2, ty = uint32_t(v * float(height)) / 2;
            const bool warpOnTop = (tx + ty) % 2 == 0;
            const float slub = warpOnTop ? hash01(tx, 0, 61) : hash01(0, ty, 62);
            const float weave = (warpOnTop ? 1.0f : 0.84f) * (0.93f + 0.1f * slub);
            const float wear = 0.9f + 0.1f * fbm(u, v, 4, 3, 63);
            return (ornament ? trim : fabric) * weave * wear;
        });
}

} // namespace lpv::engine::textures
