// Glossy reflections through the LPV on each backend: a point of a glossy Cornell floor shows the
// red (green) wall's colour when seen from where its mirror direction meets that wall, and less red
// seen from the mirrored side; gi.glossy=false leaves nothing; GL and Vulkan agree.
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/scene/BuiltinScenes.h"
#include "gi/GlossyReflections.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

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

// The march of lpv_glossy.glsl on the CPU from the read-back volumes (roughness 0.1 as the test
// floor): the finest cascade that holds the march's start half a cell inside its border, steps
// until one leaves it.
glm::vec3 referenceGlossy(const CornellFrame& f, glm::vec3 p, glm::vec3 n, glm::vec3 r) {
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
    const float band1 = glm::mix(1.0f, 2.0f / 3.0f, 0.1f);
    const glm::vec3 d = -r; // the radiance arriving along r travels along -r
    const glm::vec4 lobe(0.282094792f, 0.488602512f * band1 * d.y, 0.488602512f * band1 * d.z,
                         0.488602512f * band1 * d.x);
    glm::vec3 sum(0.0f);
    float weights = 0.0f;
    for (uint32_t step = 1; step <= gi::GlossyReflections::kSteps; ++step) {
        const glm::vec3 uvw = uvwIn(c, p + 0.5f * cell * n + r * (cell * float(step)));
        if (glm::any(glm::lessThan(uvw, glm::vec3(0.0f))) || glm::any(glm::greaterThan(uvw, glm::vec3(1.0f))))
            break;
        glm::vec3 e;
        for (int ch = 0; ch < 3; ++ch)
            e[ch] = std::max(glm::dot(sampleVolume(f.cascadeVolumes[c][size_t(ch)], uvw), lobe), 0.0f);
        sum += e / float(step);
        weights += 1.0f / float(step);
    }
    return weights > 0.0f ? sum / (weights * cell * cell) : glm::vec3(0.0f);
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
            const glm::vec3 up(0.0f, 1.0f, 0.0f);
            const glm::vec3 mirror = glm::reflect(glm::normalize(kFloorByRed - kEyeTowardRed), up);
            const glm::vec3 expected = referenceGlossy(towardRed, kFloorByRed, up, mirror);
            MESSAGE(backend.name << ": CPU march " << describe(glm::vec4(expected, 0.0f))
                                 << ", opposite direction "
                                 << describe(glm::vec4(referenceGlossy(towardRed, kFloorByRed, up, -mirror),
                                                       0.0f)));
            for (int ch = 0; ch < 3; ++ch)
                CHECK(std::fabs(red[ch] - expected[ch]) <= 0.1f * expected[ch]);
            // The lighting pass adds it (render.debug_view=glossy shows the weighted term).
            uint32_t x = 0, y = 0;
            REQUIRE(towardRed.pixelOf(kFloorByRed, x, y));
            const glm::vec4 shown = towardRed.hdr.at(x, y);
            MESSAGE(backend.name << ": glossy term after the Fresnel weight " << describe(shown));
            CHECK(shown.r > 1.2f * shown.g);

            std::vector<std::string> off = kGlossyOn;
            off.push_back("gi.glossy=false");
            const CornellFrame none = renderGlossy(*device, off, kEyeTowardRed, kFloorByRed, false);
            float maxGlossy = 0.0f, maxShown = 0.0f;
            for (const glm::vec4& t : none.glossy.texels)
                maxGlossy = std::max({maxGlossy, t.r, t.g, t.b});
            for (const glm::vec4& t : none.hdr.texels)
                maxShown = std::max({maxShown, t.r, t.g, t.b});
            CHECK(maxGlossy == 0.0f);
            CHECK(maxShown == 0.0f);
            device.expectSilent();
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
