// Reflective shadow maps drawn at the meshes' levels of detail (gi.rsm_lod_texels): the atrium's
// sun RSM draws far fewer triangles, reflects the same flux, and the frame's indirect light barely
// changes. On each backend, and GL against Vulkan.
#include "../render/CornellFrame.h"
#include "../support/Image.h"
#include "../support/TestDevice.h"
#include "engine/render/GpuScene.h"
#include "engine/render/SpecularAlbedoTexture.h"
#include "engine/scene/BuiltinScenes.h"
#include "gi/ReflectiveShadowMap.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

// The finest cascade lpv_bench uses in the atrium: 32 cells of 1 m around the court's middle.
const gi::VolumeGrid kGrid{{-16.0f, -4.0f, -16.0f}, 1.0f, 32};

struct RsmImages {
    uint64_t triangles = 0;
    Image flux, depth;
};

RsmImages renderRsm(rhi::Device& device, const engine::Scene& scene, float lodTexels) {
    const engine::GpuScene gpu(device, scene);
    const engine::SpecularAlbedoTexture specularAlbedo(device);
    gi::ReflectiveShadowMap rsm(device, 256);
    const glm::vec3 sun = scene.lights.at(0).direction;
    rsm.fit(kGrid, sun);
    RsmImages out;
    rhi::CommandList& cmd = device.beginFrame();
    out.triangles = rsm.record(cmd, gpu, specularAlbedo.texture(), sun, glm::vec3(1.0f), 0.0f, lodTexels);
    device.endFrame();
    device.waitIdle();
    out.flux = readImage(device, rsm.flux());
    out.depth = readImage(device, rsm.depth());
    return out;
}

glm::dvec3 totalFlux(const Image& flux) {
    glm::dvec3 sum(0.0);
    for (const glm::vec4& t : flux.texels)
        sum += glm::dvec3(t);
    return sum;
}

} // namespace

TEST_CASE("gi: RSM levels of detail cut the atrium's triangles and keep its reflected flux") {
    const engine::Scene scene = engine::buildAtrium(0.25f);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const RsmImages full = renderRsm(*device, scene, 0.0f);
            const RsmImages lod = renderRsm(*device, scene, 0.5f);
            const glm::dvec3 a = totalFlux(full.flux), b = totalFlux(lod.flux);
            // Texels whose depth moved by more than a texel's width (0.22 m): where the coarse
            // meshes stand elsewhere than the full ones.
            const float texelDepth = 0.22f / (5.0f * 0.5f * std::sqrt(3.0f) * 32.0f); // of the depth range
            size_t moved = 0;
            for (size_t i = 0; i < full.depth.texels.size(); ++i)
                moved += std::fabs(full.depth.texels[i].x - lod.depth.texels[i].x) > texelDepth ? 1 : 0;
            const double movedShare = double(moved) / double(full.depth.texels.size());
            MESSAGE(backend.name << ": " << full.triangles << " -> " << lod.triangles << " triangles; flux "
                                 << a.g << " -> " << b.g << "; " << 100.0 * movedShare
                                 << "% of the texels more than a texel deeper or shallower");
            CHECK(lod.triangles > 0);
            CHECK(lod.triangles * 3 < full.triangles);
            for (int c = 0; c < 3; ++c)
                CHECK(std::fabs(b[c] / a[c] - 1.0) < 0.02);
            CHECK(movedShare < 0.02);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: a spot light's RSM draws levels of detail by distance and keeps its flux") {
    // A spot over the court, looking down at the columns: its texel grows with distance, so each
    // object gets the level its nearest point to the light allows.
    const engine::Scene scene = engine::buildAtrium(0.25f);
    const engine::Light spot = engine::atriumCourtSpot();
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const engine::GpuScene gpu(*device, scene);
            const engine::SpecularAlbedoTexture specularAlbedo(*device);
            gi::ReflectiveShadowMap rsm(*device, 256, gi::RsmLight::Spot);
            RsmImages full, lod, coarse;
            for (RsmImages* out : {&full, &lod, &coarse}) {
                rhi::CommandList& cmd = device->beginFrame();
                const float lodTexels = out == &full ? 0.0f : out == &lod ? 0.5f : 4.0f;
                out->triangles = rsm.recordSpot(cmd, gpu, specularAlbedo.texture(), spot, 30.0f, lodTexels);
                device->endFrame();
                device->waitIdle();
                out->flux = readImage(*device, rsm.flux());
            }
            const glm::dvec3 a = totalFlux(full.flux), b = totalFlux(lod.flux);
            MESSAGE(backend.name << ": spot RSM " << full.triangles << " -> " << lod.triangles
                                 << " triangles (" << coarse.triangles << " within 4 texels); flux " << a.g
                                 << " -> " << b.g);
            // Its texel is 5 cm at 8 m, so at half a texel only the finest levels qualify (measured
            // 14.3k -> 9.9k); allowed more error, coarser levels follow.
            CHECK(lod.triangles < full.triangles);
            CHECK(coarse.triangles < lod.triangles);
            for (int c = 0; c < 3; ++c)
                CHECK(std::fabs(b[c] / a[c] - 1.0) < 0.02);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: RSM levels of detail change the atrium's indirect light by a few percent") {
    // The bench's cell size; the indirect light alone, as the lighting pass adds it.
    const engine::Scene scene = engine::buildAtrium(0.25f);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            const CornellFrame a = renderAtriumIndirect(*device, scene, "gi.rsm_lod_texels=0");
            const CornellFrame b = renderAtriumIndirect(*device, scene, "gi.rsm_lod_texels=0.5");
            const double la = meanLuminance(a.hdr), lb = meanLuminance(b.hdr);
            float peak = 0.0f;
            for (const glm::vec4& t : a.hdr.texels)
                peak = std::max(peak, luminance(t));
            // VPLs cluster a little elsewhere and some cross into the next cell: local changes
            // (measured: 1% of the pixels by more than a tenth of the peak, which is 15x the mean).
            const ImageDifference d = compareImages(a.hdr, b.hdr, 0.1f * peak);
            MESSAGE(backend.name << ": mean indirect luminance " << la << " with full meshes, " << lb
                                 << " with levels of detail; " << d.texelsOver << " of "
                                 << a.hdr.texels.size() << " pixels differ by more than a tenth of the peak ("
                                 << peak << ")");
            CHECK(la > 0.0);
            CHECK(std::fabs(lb / la - 1.0) < 0.03);
            CHECK(d.texelsOver < a.hdr.texels.size() / 50);
            device.expectSilent();
        }
    }
}

TEST_CASE("gi: GL and Vulkan draw the same RSM at levels of detail") {
    const engine::Scene scene = engine::buildAtrium(0.25f);
    RsmImages gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = renderRsm(*device, scene, 0.5f);
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = renderRsm(*device, scene, 0.5f);
        device.expectSilent();
    }
    CHECK(gl.triangles == vk.triangles);
    checkBackendsAgree(gl.flux, vk.flux, "RSM flux");
}
