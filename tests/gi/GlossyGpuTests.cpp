// Glossy reflections through the LPV on each backend: a point of a glossy Cornell floor shows the
// red (green) wall's colour when seen from where its mirror direction meets that wall, and less red
// seen from the mirrored side; the term is weighted by the lobe's directional albedo; surfaces not
// marched reflect the volume at their lobe's mean direction; GL and Vulkan agree; the
// lookup and the march drawn per cascade class equal the per-texel choice.
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/render/SpecularAlbedo.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/GlossyReflections.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <utility>

using namespace lpv;
using namespace lpv::test;

namespace {

// As the Cornell GI test: 32 cells of 0.17 m span the room but not its sunlit roof.
const std::vector<std::string> kGlossyOn = {"gi.enabled=true", "gi.cell_size=0.17", "gi.iterations=16",
                                            "render.ssao=false", "render.debug_view=glossy"};

// The Cornell box with a glossy white floor (and back wall and ceiling: one material), seen from
// `eye` looking at `target` with a wide lens.
engine::Scene glossyCornell(glm::vec3 eye, glm::vec3 target) {
    engine::Scene scene = engine::buildCornellBox();
    for (engine::Material& m : scene.materials)
        if (m.name == "white") m.roughness = 0.1f;
    scene.camera->position = eye;
    scene.camera->forward = glm::normalize(target - eye);
    scene.camera->verticalFov = glm::radians(75.0f);
    return scene;
}

CornellFrame renderGlossy(rhi::Device& device, const std::vector<std::string>& settings, glm::vec3 eye,
                          glm::vec3 target, bool mirroredSun) {
    return renderSceneFrame(device, glossyCornell(eye, target), settings, [&](engine::Renderer& renderer) {
        // Mirrored in x, the sun lights the green side instead of the red one.
        if (mirroredSun) renderer.sun().direction.x = -renderer.sun().direction.x;
    });
}

float redOverGreen(glm::vec4 c) {
    return c.r / std::max(c.g, 1e-9f);
}

// One floor point, on the sunlit patch by the red wall, seen from two eyes mirrored about it in x:
// from `toward` its mirror direction (-0.69, 0.51, -0.51) meets the red wall half a metre away,
// from `away` it runs into the room. (Eyes close by: the room has no space for a far eye beside the
// wall.)
const glm::vec3 kFloorByRed{-2.2f, 0.0f, 1.5f};
const glm::vec3 kEyeTowardRed = kFloorByRed + glm::vec3(0.8f, 0.6f, 0.6f);
const glm::vec3 kEyeAwayFromRed = kFloorByRed + glm::vec3(-0.4f, 0.3f, 0.3f);
// The same toward the green wall, mirrored in x (eye and ray stay clear of the short box).
const glm::vec3 kFloorByGreen{2.2f, 0.0f, 1.5f};
const glm::vec3 kEyeTowardGreen = kFloorByGreen + glm::vec3(-0.8f, 0.6f, 0.6f);

// Trilinear, clamp to edge, texel centres at half-integers: as the GPU samples the volume.
glm::vec4 sampleVolume(const Image& v, glm::vec3 uvw) {
    const glm::vec3 t = uvw * glm::vec3(v.width, v.height, v.depth) - 0.5f;
    const glm::vec3 base = glm::floor(t), f = t - base;
    const auto clampTo = [](int i, uint32_t n) { return uint32_t(std::clamp(i, 0, int(n) - 1)); };
    glm::vec4 sum(0.0f);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 o((corner & 1) != 0, (corner & 2) != 0, (corner & 4) != 0);
        const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(o));
        const glm::ivec3 c = glm::ivec3(base) + o;
        sum += w.x * w.y * w.z * v.at(clampTo(c.x, v.width), clampTo(c.y, v.height), clampTo(c.z, v.depth));
    }
    return sum;
}

// lpv_lookup.glsl's keptInside, in cell coordinates (cell centres at whole numbers) of q, the
// surface point p and the camera: per axis, the filter's share of the cell across from the one q
// lies in, scaled by the transmittance of the face between them, unless the camera's ray to p
// crossed that face's plane within a cell of q: then the camera's side of it.
glm::vec3 keptInside(const Image& faces, glm::vec3 t, glm::vec3 p, glm::vec3 camera) {
    const int n = int(faces.width);
    const glm::vec3 base = glm::floor(t);
    glm::vec3 f = t - base;
    const glm::ivec3 home = glm::ivec3(base) + glm::ivec3(glm::greaterThanEqual(f, glm::vec3(0.5f)));
    for (int a = 0; a < 3; ++a) {
        glm::ivec3 upper = home;
        if (f[a] < 0.5f) upper[a] += 1;
        upper = glm::clamp(upper, glm::ivec3(0), glm::ivec3(n - 1));
        const float open = faces.at(uint32_t(upper.x), uint32_t(upper.y), uint32_t(upper.z))[a];
        const float plane = base[a] + 0.5f;
        bool upperHome = f[a] >= 0.5f;
        const bool cameraAbove = camera[a] >= plane;
        if (upperHome != cameraAbove && (p[a] >= plane) == upperHome && open < 1.0f) {
            const glm::vec3 crossing = glm::mix(camera, p, (plane - camera[a]) / (p[a] - camera[a]));
            glm::vec3 away = glm::abs(crossing - t);
            away[a] = 0.0f;
            if (std::max({away.x, away.y, away.z}) <= 1.0f) upperHome = cameraAbove;
        }
        f[a] = upperHome ? 1.0f - (1.0f - f[a]) * open : f[a] * open;
    }
    return base + f + 0.5f;
}

// The GGX lobe as glossy_lobes.glsl evaluates it: per channel of F0 the basis at the lobe's mean
// light direction (the table's directions, x along n and y along the mirror direction's part
// across n; the light travels along the negated direction), and the march's direction, the mean
// direction of F0's luminance, normalized.
struct MeanLobes {
    glm::vec4 channel[3];
    glm::vec3 direction{0.0f};
};

glm::vec4 shBasisAt(glm::vec3 w, float band0, float band1) {
    return glm::vec4(band0, band1 * w.y, band1 * w.z, band1 * w.x);
}

MeanLobes meanLobes(glm::vec3 n, glm::vec3 v, const engine::SpecularAlbedo& s, glm::vec3 f0) {
    const glm::vec3 across = glm::reflect(-v, n) - n * glm::dot(n, v);
    const glm::vec3 t = glm::length(across) > 1e-5f ? glm::normalize(across) : glm::vec3(0.0f);
    const auto mean = [&](float f) {
        const glm::vec2 m = (f * s.scaleDirection + s.biasDirection) / (f * s.scale + s.bias);
        return m.x * n + m.y * t;
    };
    MeanLobes lobes;
    for (int ch = 0; ch < 3; ++ch)
        lobes.channel[ch] = shBasisAt(-mean(f0[ch]), 0.282094792f, 0.488602512f);
    lobes.direction = glm::normalize(mean(glm::dot(f0, glm::vec3(0.2126f, 0.7152f, 0.0722f))));
    return lobes;
}

// The march of lpv_glossy.glsl on the CPU from the read-back volumes: the finest cascade that holds
// the march's start half a cell inside its border, steps along `r` until one leaves it, each
// channel through its lobe.
glm::vec3 referenceGlossy(const CornellFrame& f, glm::vec3 p, glm::vec3 n, glm::vec3 r,
                          const glm::vec4 (&lobe)[3]) {
    const auto uvwIn = [&](size_t c, glm::vec3 q) {
        const gi::VolumeGrid& g = f.cascadeGrids[c];
        return (q - g.origin) / (g.cellSize * float(g.size));
    };
    size_t c = 0;
    while (c + 1 < f.cascadeGrids.size()) {
        const float margin = 0.5f / float(f.cascadeGrids[c].size);
        const glm::vec3 uvw = uvwIn(c, p + 0.5f * f.cascadeGrids[c].cellSize * n);
        if (glm::all(glm::greaterThanEqual(uvw, glm::vec3(margin))) &&
            glm::all(glm::lessThanEqual(uvw, glm::vec3(1.0f - margin))))
            break;
        ++c;
    }
    const float cell = f.cascadeGrids[c].cellSize;
    glm::vec3 sum(0.0f);
    float weights = 0.0f;
    for (uint32_t step = 1; step <= gi::GlossyReflections::kSteps; ++step) {
        const glm::vec3 uvw = uvwIn(c, p + 0.5f * cell * n + r * (cell * float(step)));
        if (glm::any(glm::lessThan(uvw, glm::vec3(0.0f))) || glm::any(glm::greaterThan(uvw, glm::vec3(1.0f))))
            break;
        glm::vec3 e;
        for (int ch = 0; ch < 3; ++ch)
            e[ch] = std::max(glm::dot(sampleVolume(f.cascadeVolumes[c][size_t(ch)], uvw), lobe[ch]), 0.0f);
        sum += e / float(step);
        weights += 1.0f / float(step);
    }
    return weights > 0.0f ? sum / (weights * cell * cell) : glm::vec3(0.0f);
}

glm::vec3 referenceGlossy(const CornellFrame& f, glm::vec3 p, glm::vec3 n, const MeanLobes& lobes) {
    return referenceGlossy(f, p, n, lobes.direction, lobes.channel);
}

// The march as it was before it took the lookup's lobes (kept to show the test tells them apart):
// along the mirror direction, band 1 narrowed by mix(1, 2/3, roughness) for every channel.
glm::vec3 mirrorMarch(const CornellFrame& f, glm::vec3 p, glm::vec3 n, glm::vec3 v, float roughness) {
    const glm::vec3 r = glm::reflect(-v, n);
    const glm::vec4 lobe = shBasisAt(-r, 0.282094792f, 0.488602512f * glm::mix(1.0f, 2.0f / 3.0f, roughness));
    const glm::vec4 lobes[3] = {lobe, lobe, lobe};
    return referenceGlossy(f, p, n, r, lobes);
}

// The lookup's two answers at a surface point.
struct LookedUp {
    glm::vec3 irradiance{0.0f}, glossy{0.0f};
};

// lpv_lookup.glsl on the CPU from the read-back volumes, damping off: each cascade the point's
// blend weights give a share (finest first) answers half a cell out along n, with the cosine lobe
// around -n for the irradiance and, per channel of F0, the basis at the lobe's mean light direction
// (the table's directions, x along n and y along the mirror direction's part across n) for the
// glossy radiance.
LookedUp referenceLookup(const CornellFrame& f, glm::vec3 p, glm::vec3 n, glm::vec3 v,
                         engine::SpecularAlbedo s, glm::vec3 f0) {
    const glm::vec4 cosine = shBasisAt(-n, 0.886226925f, 1.023326708f);
    const MeanLobes glossyLobes = meanLobes(n, v, s, f0);
    const auto inCascade = [&](size_t c) {
        const gi::VolumeGrid& g = f.cascadeGrids[c];
        glm::vec3 uvw = (p + 0.5f * g.cellSize * n - g.origin) / (g.cellSize * float(g.size));
        if (c < f.cascadeFaces.size() && f.cascadeFaces[c].width > 0) {
            const auto cells = [&](glm::vec3 w) { return (w - g.origin) / g.cellSize - 0.5f; };
            uvw = keptInside(f.cascadeFaces[c], cells(p + 0.5f * g.cellSize * n), cells(p),
                             cells(f.camera.position)) /
                  float(g.size);
        }
        LookedUp r;
        if (glm::any(glm::lessThan(uvw, glm::vec3(0.0f))) || glm::any(glm::greaterThan(uvw, glm::vec3(1.0f))))
            return r;
        const float area = g.cellSize * g.cellSize;
        for (int ch = 0; ch < 3; ++ch) {
            const glm::vec4 sh = sampleVolume(f.cascadeVolumes[c][size_t(ch)], uvw);
            r.irradiance[ch] = std::max(glm::dot(sh, cosine), 0.0f) / area;
            r.glossy[ch] = std::max(glm::dot(sh, glossyLobes.channel[ch]), 0.0f) / area;
        }
        return r;
    };
    // cascade_region.glsl's insideness with the lookup's band (a quarter of the half-extent),
    // smoothed.
    const auto blendWeight = [&](size_t c) {
        const gi::VolumeGrid& g = f.cascadeGrids[c];
        const glm::vec3 uvw = (p - g.origin) / (g.cellSize * float(g.size));
        const float margin = 1.0f / float(g.size);
        const glm::vec3 e = glm::min(uvw - margin, (1.0f - margin) - uvw);
        const float x = std::clamp(std::min({e.x, e.y, e.z}) / (0.25f * (0.5f - margin)), 0.0f, 1.0f);
        return x * x * (3.0f - 2.0f * x);
    };
    LookedUp sum;
    const auto add = [&](const LookedUp& l, float w) {
        sum.irradiance += w * l.irradiance;
        sum.glossy += w * l.glossy;
    };
    float left = 1.0f;
    for (size_t c = 0; c + 1 < f.cascadeGrids.size() && left > 0.0f; ++c) {
        const float w = blendWeight(c);
        if (w > 0.0f) add(inCascade(c), left * w);
        left *= 1.0f - w;
    }
    if (left > 0.0f) add(inCascade(f.cascadeGrids.size() - 1), left);
    return sum;
}

// The glossy Cornell box seen from `eye` toward the floor's middle, its floor given a material of
// its own (so a metal floor leaves the walls' light as it is).
engine::Scene cornellWithFloor(glm::vec3 eye, float roughness, float metallic) {
    engine::Scene scene = glossyCornell(eye, {0.0f, 0.0f, 0.5f});
    engine::Material floor = scene.materials[scene.meshes.front().material];
    floor.name = "test floor";
    floor.roughness = roughness;
    floor.metallic = metallic;
    scene.materials.push_back(floor);
    for (engine::Mesh& mesh : scene.meshes)
        if (mesh.name == "floor") mesh.material = uint32_t(scene.materials.size() - 1);
    return scene;
}

// Whether a surface point lies on the floor (height 0) and not on the bottom row of a wall, which
// lies at height 0 too (the walls' inner faces are at x = +-2.75 and z = -2.75).
bool onFloor(glm::vec3 p) {
    return std::fabs(p.y) <= 2e-3f && std::fabs(p.x) < 2.74f && p.z > -2.74f;
}

glm::vec4 glossyAt(const CornellFrame& f, glm::vec3 world) {
    uint32_t x = 0, y = 0;
    REQUIRE(f.pixelOf(world, x, y));
    return f.glossyAt(x, y);
}

} // namespace

TEST_CASE("gi: a glossy floor reflects the wall in its mirror direction") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // The default sun lights the red side.
            const CornellFrame towardRed =
                renderGlossy(*device, kGlossyOn, kEyeTowardRed, kFloorByRed, false);
            const CornellFrame awayFromRed =
                renderGlossy(*device, kGlossyOn, kEyeAwayFromRed, kFloorByRed, false);
            const CornellFrame towardGreen =
                renderGlossy(*device, kGlossyOn, kEyeTowardGreen, kFloorByGreen, true);
            const glm::vec4 red = glossyAt(towardRed, kFloorByRed),
                            notRed = glossyAt(awayFromRed, kFloorByRed);
            const glm::vec4 green = glossyAt(towardGreen, kFloorByGreen);
            MESSAGE(backend.name << ": glossy radiance on the floor by the red wall, reflecting it "
                                 << describe(red) << ", reflecting the room " << describe(notRed)
                                 << "; by the green wall (mirrored sun), reflecting it " << describe(green));
            // The wall's colour in the mirror direction, with a 20% margin ...
            CHECK(red.r > 1.2f * red.g);
            CHECK(green.g > 1.2f * green.r);
            // ... and clearly less of it at the same point in the other direction. (Not checked on
            // the green side: there the sunlit top of the short box puts more white light around
            // the point, and the L1 volume keeps too little of the direction to tell them apart.)
            CHECK(redOverGreen(notRed) < 0.9f * redOverGreen(red));
            // The GPU march against the CPU one at the point (the pixel's centre is a few mm from
            // it): 10%, where gathering the opposite direction would be off by 60%.
            const glm::vec3 up(0.0f, 1.0f, 0.0f), v = glm::normalize(kEyeTowardRed - kFloorByRed);
            const MeanLobes lobes =
                meanLobes(up, v, engine::specularAlbedoTable().at(v.y, 0.1f), glm::vec3(0.04f));
            const glm::vec3 expected = referenceGlossy(towardRed, kFloorByRed, up, lobes);
            // The opposite: the lobe turned around.
            glm::vec4 opposite[3];
            for (int ch = 0; ch < 3; ++ch)
                opposite[ch] =
                    glm::vec4(lobes.channel[ch].x,
                              -glm::vec3(lobes.channel[ch].y, lobes.channel[ch].z, lobes.channel[ch].w));
            MESSAGE(backend.name << ": CPU march " << describe(glm::vec4(expected, 0.0f))
                                 << ", opposite direction "
                                 << describe(glm::vec4(referenceGlossy(towardRed, kFloorByRed, up,
                                                                       -lobes.direction, opposite),
                                                       0.0f)));
            for (int ch = 0; ch < 3; ++ch)
                CHECK(std::fabs(red[ch] - expected[ch]) <= 0.1f * expected[ch]);
            // The lighting pass adds it (render.debug_view=glossy shows the weighted term).
            uint32_t x = 0, y = 0;
            REQUIRE(towardRed.pixelOf(kFloorByRed, x, y));
            const glm::vec4 shown = towardRed.hdr.at(x, y);
            MESSAGE(backend.name << ": glossy term after the specular weight " << describe(shown));
            CHECK(shown.r > 1.2f * shown.g);

            device.expectSilent();
        }
    }
}

// The lighting pass weighs the glossy radiance by the GGX lobe's directional albedo
// (engine/render/SpecularAlbedo.h), F0 x scale + bias: on floor pixels from near the eye (cos 0.7)
// to the back wall (cos 0.1), for the white floor as a smooth (0.1) and a rough (0.6) dielectric
// (F0 4%) and as a metal (F0 its albedo), the shown term over the marched radiance is the table's
// weight at the pixel's own view angle. (The former
// weight, Schlick x (1 - roughness), is 2.7x the table's at cos 0.1 and half of it at cos 0.7 for
// roughness 0.6.)
TEST_CASE("gi: the glossy term is weighted by the lobe's directional albedo") {
    const engine::SpecularAlbedoTable& table = engine::specularAlbedoTable();
    const glm::vec3 eye(0.0f, 0.5f, 2.5f);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // Dielectric (F0 4%), smooth and rough, and a metal (F0 = its albedo, 0.73).
            for (const auto& [roughness, metallic] : {std::pair{0.1f, 0.0f}, {0.6f, 0.0f}, {0.3f, 1.0f}}) {
                const engine::Scene scene = cornellWithFloor(eye, roughness, metallic);
                const float f0 = metallic > 0.0f ? 0.73f : 0.04f;
                std::vector<std::string> settings = kGlossyOn;
                settings.push_back("gi.resolution=full"); // the marched texel is the pixel's own
                const CornellFrame f = renderSceneFrame(*device, scene, settings);
                size_t compared = 0, dim = 0;
                float worst = 0.0f, cosMin = 1.0f, cosMax = 0.0f;
                // Every 8th pixel each way that shows the floor (its surface point at height 0).
                for (uint32_t py = 4; py < f.height; py += 8)
                    for (uint32_t px = 4; px < f.width; px += 8) {
                        if (f.depth.at(px, py).x >= 1.0f) continue;
                        const glm::vec3 p = f.worldAt(px, py);
                        if (!onFloor(p)) continue;
                        const float cosView = glm::normalize(eye - p).y;
                        const glm::vec4 marched = f.glossyAt(px, py), shown = f.hdr.at(px, py);
                        const float in = marched.r + marched.g + marched.b;
                        // Halves keep their 11 bits from 6.1e-5 up; below it (the dim floor under
                        // the eye, the weight's 4% on a faint march) they are subnormal.
                        if (std::min({shown.r, shown.g, shown.b}) < 6.2e-5f) {
                            ++dim;
                            continue;
                        }
                        const engine::SpecularAlbedo s = table.at(cosView, roughness);
                        const float expected = f0 * s.scale + s.bias;
                        const float measured = (shown.r + shown.g + shown.b) / in;
                        worst = std::max(worst, std::fabs(measured - expected) / expected);
                        cosMin = std::min(cosMin, cosView);
                        cosMax = std::max(cosMax, cosView);
                        ++compared;
                    }
                MESSAGE(backend.name << ", roughness " << roughness << ", F0 " << f0 << ": " << compared
                                     << " floor points (and " << dim << " too dim to tell), cos(view) "
                                     << cosMin << " to " << cosMax
                                     << ", largest relative difference from the table's weight " << worst);
                CHECK(compared >= 16);
                CHECK(cosMin < 0.15f);
                // A metal floor reflects none of the sun's patch into the room (no diffuse, so no
                // VPLs): only its far half is bright enough to compare (measured cos up to 0.48).
                CHECK(cosMax > (metallic > 0.0f ? 0.4f : 0.6f));
                // RGBA16F targets, an RG16F table and the GPU's filtering weights: 1% (measured
                // 0.1%).
                CHECK(worst <= 0.01f);
            }
            device.expectSilent();
        }
    }
}

// Where the march does not run (a surface too rough for it) the lookup writes the glossy radiance:
// the volume at the surface point (half a cell out, as the irradiance) evaluated at the GGX lobe's
// mean light direction per channel (SpecularAlbedo.h's directions for the channel's F0), blended
// across cascades as the irradiance is; with gi.glossy=false, the cosine lobe's E / pi. Each floor
// pixel's glossy target equals that, computed here on the CPU from the read-back volumes and the
// table, for a fully rough metal floor (which has no diffuse, and so would go black in indirect
// light without it), a dielectric rougher than gi.glossy_max_roughness and a smooth metal with the
// march off; the lighting pass weighs it by the table's F0 x scale + bias. The reference is checked
// against the GPU's irradiance too, and the mean direction must make a difference: at some pixels
// of the dielectric the cosine lobe around the normal is off by more than 10%.
TEST_CASE("gi: surfaces the glossy march skips reflect the volume at their lobe's mean direction") {
    const engine::SpecularAlbedoTable& table = engine::specularAlbedoTable();
    const glm::vec3 eye(0.0f, 0.5f, 2.5f);
    struct Case {
        float roughness, metallic;
        const char* setting;
    };
    const Case cases[] = {{1.0f, 1.0f, "gi.glossy_max_roughness=1"},
                          {0.5f, 0.0f, "gi.glossy_max_roughness=0.4"},
                          {0.3f, 1.0f, "gi.glossy=false"},
                          // Only the finest cascade's lookup kept to its faces, the coarse ones
                          // filtering plainly (the default keeps every one's; the reference mirrors both).
                          {1.0f, 1.0f, "gi.lookup_occlusion=false"}};
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            for (const Case& c : cases) {
                const engine::Scene scene = cornellWithFloor(eye, c.roughness, c.metallic);
                const float f0 = c.metallic > 0.0f ? 0.73f : 0.04f;
                std::vector<std::string> settings = kGlossyOn;
                settings.push_back("gi.resolution=full"); // the looked-up texel is the pixel's own
                settings.push_back("gi.damping=false");   // the reference below leaves it out
                settings.push_back(c.setting);
                const CornellFrame f = renderSceneFrame(*device, scene, settings);
                const bool glossyOn = std::string(c.setting) != "gi.glossy=false";
                size_t compared = 0, dim = 0, directional = 0;
                float worst = 0.0f, worstIrradiance = 0.0f, worstWeight = 0.0f, largestCosineOff = 0.0f;
                for (uint32_t py = 4; py < f.height; py += 8)
                    for (uint32_t px = 4; px < f.width; px += 8) {
                        if (f.depth.at(px, py).x >= 1.0f) continue;
                        const glm::vec3 p = f.worldAt(px, py);
                        if (!onFloor(p)) continue;
                        const glm::vec3 target = glm::vec3(f.glossyAt(px, py)),
                                        shown = glm::vec3(f.hdr.at(px, py));
                        // Halves keep their 11 bits from 6.1e-5 up.
                        if (std::min({target.r, target.g, target.b, shown.r, shown.g, shown.b}) < 6.2e-5f) {
                            ++dim;
                            continue;
                        }
                        const glm::vec3 up(0.0f, 1.0f, 0.0f), v = glm::normalize(eye - p);
                        const engine::SpecularAlbedo s = table.at(v.y, c.roughness);
                        LookedUp expected = referenceLookup(f, p, up, v, s, glm::vec3(f0));
                        const glm::vec3 lobeMean = expected.glossy;
                        if (!glossyOn) expected.glossy = expected.irradiance / 3.14159265f;
                        const glm::vec3 irradiance = glm::vec3(f.indirect.at(px, py));
                        for (int ch = 0; ch < 3; ++ch) {
                            worst = std::max(worst, std::fabs(target[ch] - expected.glossy[ch]) /
                                                        expected.glossy[ch]);
                            worstIrradiance = std::max(worstIrradiance,
                                                       std::fabs(irradiance[ch] - expected.irradiance[ch]) /
                                                           expected.irradiance[ch]);
                            const float cosine = expected.irradiance[ch] / 3.14159265f;
                            largestCosineOff =
                                std::max(largestCosineOff, std::fabs(cosine - lobeMean[ch]) / lobeMean[ch]);
                        }
                        if (std::fabs(expected.irradiance.r / 3.14159265f - lobeMean.r) > 0.1f * lobeMean.r)
                            ++directional;
                        const float weight = f0 * s.scale + s.bias;
                        worstWeight = std::max(worstWeight, std::fabs((shown.r + shown.g + shown.b) /
                                                                          (target.r + target.g + target.b) -
                                                                      weight) /
                                                                weight);
                        ++compared;
                    }
                MESSAGE(backend.name << ", roughness " << c.roughness << ", F0 " << f0 << ", "
                                     << std::string(c.setting) << ": " << compared << " floor points (and "
                                     << dim << " too dim to tell); largest relative difference from the "
                                     << "reference: glossy " << worst << ", irradiance " << worstIrradiance
                                     << "; shown term from the table's weight x target " << worstWeight
                                     << "; the cosine lobe around n off from the mean direction's by up to "
                                     << largestCosineOff << " (" << directional
                                     << " points by more than 10%)");
                CHECK(compared >= 100);
                // RGBA16F volumes and targets, an RGBA16F table and the GPU's filtering weights: 1%.
                CHECK(worst <= 0.01f);
                CHECK(worstIrradiance <= 0.01f);
                CHECK(worstWeight <= 0.01f);
                // Seen from the side the dielectric's mean direction matters (the fully rough metal's
                // lobe is nearly the cosine lobe: measured 0.4% off).
                if (c.metallic == 0.0f) CHECK(directional >= 10);
            }
            device.expectSilent();
        }
    }
}

// Where the march runs it evaluates the lookup's lobe (per channel of F0 the basis at the GGX lobe's
// mean light direction) at a few cells along the mean direction of F0's luminance, so that march
// and lookup differ only in where they sample and the fade between them (gi.glossy_max_roughness)
// blends two answers for the same lobe. Each floor pixel's glossy target equals that march computed
// on the CPU from the read-back volumes and the table, for a smooth and a rough dielectric and a
// metal floor, all marched in full; and the lobe must make a difference: for the rough dielectric
// the former march (the mirror direction, band 1 narrowed by mix(1, 2/3, roughness) for every
// channel) is off by more than 10% at some of the points.
TEST_CASE("gi: the glossy march gathers the lookup's lobe along its mean direction") {
    const engine::SpecularAlbedoTable& table = engine::specularAlbedoTable();
    const glm::vec3 eye(0.0f, 0.5f, 2.5f);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            for (const auto& [roughness, metallic] : {std::pair{0.1f, 0.0f}, {0.7f, 0.0f}, {0.5f, 1.0f}}) {
                const engine::Scene scene = cornellWithFloor(eye, roughness, metallic);
                const float f0 = metallic > 0.0f ? 0.73f : 0.04f;
                std::vector<std::string> settings = kGlossyOn;
                settings.push_back("gi.resolution=full"); // the marched texel is the pixel's own
                const CornellFrame f = renderSceneFrame(*device, scene, settings);
                size_t compared = 0, dim = 0, formerOff = 0;
                float worst = 0.0f, largestFormerOff = 0.0f;
                for (uint32_t py = 4; py < f.height; py += 8)
                    for (uint32_t px = 4; px < f.width; px += 8) {
                        if (f.depth.at(px, py).x >= 1.0f) continue;
                        const glm::vec3 p = f.worldAt(px, py);
                        if (!onFloor(p)) continue;
                        const glm::vec3 target = glm::vec3(f.glossyAt(px, py));
                        // Halves keep their 11 bits from 6.1e-5 up.
                        if (std::min({target.r, target.g, target.b}) < 6.2e-5f) {
                            ++dim;
                            continue;
                        }
                        const glm::vec3 up(0.0f, 1.0f, 0.0f), v = glm::normalize(eye - p);
                        const glm::vec3 expected = referenceGlossy(
                            f, p, up, meanLobes(up, v, table.at(v.y, roughness), glm::vec3(f0)));
                        const glm::vec3 former = mirrorMarch(f, p, up, v, roughness);
                        float off = 0.0f;
                        for (int ch = 0; ch < 3; ++ch) {
                            worst = std::max(worst, std::fabs(target[ch] - expected[ch]) / expected[ch]);
                            off = std::max(off, std::fabs(former[ch] - expected[ch]) / expected[ch]);
                        }
                        largestFormerOff = std::max(largestFormerOff, off);
                        if (off > 0.1f) ++formerOff;
                        ++compared;
                    }
                MESSAGE(backend.name << ", roughness " << roughness << ", F0 " << f0 << ": " << compared
                                     << " floor points (and " << dim << " too dim to tell); largest relative "
                                     << "difference from the CPU march " << worst
                                     << "; the former march off by up to " << largestFormerOff << " ("
                                     << formerOff << " points by more than 10%)");
                // A metal floor reflects none of the sun's patch into the room (no diffuse, so no
                // VPLs): fewer of its points are bright enough to compare (measured 62).
                CHECK(compared >= (metallic > 0.0f ? 40u : 100u));
                // RGBA16F volumes and targets, an RGBA16F table and the GPU's filtering weights: 1%.
                CHECK(worst <= 0.01f);
                if (roughness > 0.5f && metallic == 0.0f) CHECK(formerOff >= 10);
            }
            device.expectSilent();
        }
    }
}

// gi.glossy_max_roughness: the test floor (and back wall and ceiling, roughness 0.1) is marched in
// full by default, half 0.05 below the limit and not at all above it, on each backend, drawn per
// cascade class or per texel (rhi::Caps::maskedBranches). The volumes do not depend on it, so every
// texel must be the march (the default), the lookup's reflection (above the limit), or their mean
// 0.05 below the limit (to the RGBA16F G-buffer's rounding of 0.1: 0.09998).
TEST_CASE("gi: surfaces rougher than gi.glossy_max_roughness get no glossy march, and it fades out below") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            for (const bool masked : {false, true}) {
                rhi::DeviceConfig config;
                config.maskedBranches = masked;
                TestDevice device(backend, config);
                const auto render = [&](const char* setting) {
                    std::vector<std::string> settings = kGlossyOn;
                    if (setting) settings.push_back(setting);
                    return renderGlossy(*device, settings, kEyeTowardRed, kFloorByRed, false);
                };
                const CornellFrame full = render(nullptr), faded = render("gi.glossy_max_roughness=0.15"),
                                   none = render("gi.glossy_max_roughness=0.09");
                float peak = 0.0f, offMean = 0.0f;
                for (const glm::vec4& t : full.glossy.texels)
                    peak = std::max({peak, t.r, t.g, t.b});
                size_t marched = 0;
                for (size_t i = 0; i < full.glossy.texels.size(); ++i) {
                    const glm::vec3 f(full.glossy.texels[i]), n(none.glossy.texels[i]);
                    const glm::vec3 march = glm::abs(f - n);
                    if (std::max({march.r, march.g, march.b}) > 1e-3f * peak) ++marched;
                    const glm::vec3 d = glm::abs(glm::vec3(faded.glossy.texels[i]) - 0.5f * (f + n));
                    offMean = std::max({offMean, d.r, d.g, d.b});
                }
                const std::string path = masked ? "classes" : "per texel";
                MESSAGE(backend.name << ", " << path << ": " << marched
                                     << " texels where the march changes the "
                                     << "lookup's value, peak " << peak
                                     << "; at 0.15 the largest difference from "
                                     << "the mean of march and lookup " << offMean);
                CHECK(marched > 1000);
                CHECK(offMean <= 1e-3f * peak);
                device.expectSilent();
            }
        }
    }
}

TEST_CASE("gi: GL and Vulkan compute the same glossy reflections") {
    CornellFrame gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = renderGlossy(*device, kGlossyOn, kEyeTowardRed, kFloorByRed, false);
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = renderGlossy(*device, kGlossyOn, kEyeTowardRed, kFloorByRed, false);
        device.expectSilent();
    }
    // As the indirect light: 1% of the brightest value per channel, on 99% of the pixels.
    checkBackendsAgree(gl.glossy, vk.glossy, "glossy");
}

namespace {

// Each lookup texel's cascade class as cascade_classify_body.glsl finds it, from the read-back depth
// (the lookup's cascade and whether it lies in the blend band; the glossy march's cascade needs the
// normal, which the frame does not keep): counts by 2 x cascade + band.
std::vector<uint32_t> lookupClassCounts(const CornellFrame& f) {
    std::vector<uint32_t> counts(2 * f.cascadeGrids.size(), 0);
    const uint32_t d = f.indirectDivisor;
    for (uint32_t ty = 0; ty < f.indirect.height; ++ty)
        for (uint32_t tx = 0; tx < f.indirect.width; ++tx) {
            const uint32_t x = std::min(tx * d, f.width - 1), y = std::min(ty * d, f.height - 1);
            if (f.depth.at(x, y).x >= 1.0f) continue;
            const glm::vec3 p = f.worldAt(x, y);
            size_t c = f.cascadeGrids.size() - 1;
            bool band = false;
            for (size_t k = 0; k + 1 < f.cascadeGrids.size(); ++k) {
                const gi::VolumeGrid& g = f.cascadeGrids[k];
                const glm::vec3 uvw = (p - g.origin) / (g.cellSize * float(g.size));
                const float margin = 1.0f / float(g.size);
                const glm::vec3 e = glm::min(uvw - margin, (1.0f - margin) - uvw);
                const float inside = std::min({e.x, e.y, e.z}) / (0.25f * (0.5f - margin));
                if (inside > 0.0f) {
                    c = k;
                    band = inside < 1.0f;
                    break;
                }
            }
            ++counts[2 * c + (band ? 1 : 0)];
        }
    return counts;
}

// Texels of `a` and `b` that differ by more than 1e-3 of the peak in a channel.
size_t differingTexels(const Image& a, const Image& b, float& peak, float& largest) {
    REQUIRE(a.texels.size() == b.texels.size());
    peak = largest = 0.0f;
    for (const glm::vec4& t : a.texels)
        peak = std::max({peak, t.r, t.g, t.b});
    size_t differing = 0;
    for (size_t i = 0; i < a.texels.size(); ++i) {
        const glm::vec4 d = glm::abs(a.texels[i] - b.texels[i]);
        const float m = std::max({d.r, d.g, d.b});
        largest = std::max(largest, m);
        if (m > 1e-3f * peak) ++differing;
    }
    return differing;
}

} // namespace

// A device that runs both sides of every branch (rhi::Caps::maskedBranches) classifies the lookup
// texels by cascade and draws each class on its own (gi/CascadeClasses.h); a GPU chooses per texel
// with branches. Both must give the same indirect and glossy light, on each backend: from the
// glossy floor's eye (the floor lies on the finest cascade's border, so the march runs in a finer
// cascade than the lookup) and from the room's camera (two cascades and a blend band: 2,500 and
// 700 texels). Measured: bit-identical on every backend.
TEST_CASE("gi: cascade-class draws give the per-texel choice's indirect and glossy light") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            const auto render = [&](bool masked, const engine::Scene& scene) {
                rhi::DeviceConfig config;
                config.maskedBranches = masked;
                TestDevice device(backend, config);
                REQUIRE(device->caps().maskedBranches == masked);
                CornellFrame f = renderSceneFrame(*device, scene, kGlossyOn);
                device.expectSilent();
                return f;
            };
            engine::Scene room = glossyCornell(kEyeTowardRed, kFloorByRed);
            room.camera = engine::buildCornellBox().camera;
            uint32_t cascadesSeen = 0, inBands = 0; // bit c: cascade c has texels in either frame
            for (const engine::Scene& scene : {glossyCornell(kEyeTowardRed, kFloorByRed), room}) {
                const CornellFrame branching = render(false, scene), classified = render(true, scene);
                const std::vector<uint32_t> classes = lookupClassCounts(classified);
                std::string described;
                for (size_t c = 0; 2 * c < classes.size(); ++c) {
                    described +=
                        " " + std::to_string(classes[2 * c]) + "/" + std::to_string(classes[2 * c + 1]);
                    inBands += classes[2 * c + 1];
                    if (classes[2 * c] + classes[2 * c + 1] > 0) cascadesSeen |= 1u << c;
                }
                float peak = 0.0f, largest = 0.0f;
                const size_t indirectOff =
                    differingTexels(branching.indirect, classified.indirect, peak, largest);
                MESSAGE(backend.name << ": texels by cascade and band (inside, in band per cascade):"
                                     << described << "; indirect: " << indirectOff
                                     << " texels off, largest difference " << largest << " of peak " << peak);
                CHECK(indirectOff == 0);
                CHECK(peak > 0.0f);
                const size_t glossyOff = differingTexels(branching.glossy, classified.glossy, peak, largest);
                MESSAGE(backend.name << ": glossy: " << glossyOff << " texels off, largest difference "
                                     << largest << " of peak " << peak);
                CHECK(glossyOff == 0);
                CHECK(peak > 0.0f);
            }
            // The frames must hold texels of several cascades and of blend bands, or the
            // comparison shows little.
            CHECK(std::popcount(cascadesSeen) >= 2);
            CHECK(inBands > 500);
        }
    }
}
