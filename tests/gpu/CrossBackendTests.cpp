// The same draws on OpenGL and Vulkan must produce the same pixels.
#include "RhiScenarios.h"

#include "../support/TestDevice.h"

#include <doctest/doctest.h>

using namespace lpv;
using namespace lpv::test;

// Tolerance: both drivers rasterize with the same fill rules, so interior pixels must match to
// one 8-bit step; edge pixels may differ by coverage, and at most 0.5% of the pixels may exceed it.
TEST_CASE("rhi: GL and Vulkan draw the same MRT image") {
    MrtImages gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = renderIndexedMrt(*device);
        device.expectSilent();
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = renderIndexedMrt(*device);
        device.expectSilent();
    }
    const uint32_t allowed = gl.color.width * gl.color.height / 200;
    const ImageDifference color = compareImages(gl.color, vk.color, 1.0f / 255.0f + 1e-4f);
    const ImageDifference second = compareImages(gl.second, vk.second, 1e-3f);
    const ImageDifference depth = compareImages(gl.depth, vk.depth, 1e-5f);
    MESSAGE("color max diff " << color.maxAbs << ", " << color.texelsOver << " over tolerance");
    CHECK(color.texelsOver <= allowed);
    CHECK(second.texelsOver <= allowed);
    CHECK(depth.texelsOver <= allowed);
}

TEST_CASE("rhi: GL and Vulkan compute the same volume") {
    Image gl, vk;
    {
        TestDevice device(backendByName("gl-egl"));
        gl = fillVolume(*device);
    }
    {
        TestDevice device(backendByName("vulkan"));
        vk = fillVolume(*device);
    }
    // Same half-precision rounding of nearly the same float: at most one half ulp near 1.0 apart.
    const ImageDifference d = compareImages(gl, vk, 1e-3f);
    CHECK_MESSAGE(d.texelsOver == 0, "max diff " << d.maxAbs);
}
