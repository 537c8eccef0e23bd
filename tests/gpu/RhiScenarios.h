// Small GPU workloads that every backend must run identically. Each returns what it read back so
// per-backend tests can check values and the cross-backend test can compare images.
#pragma once

#include "../support/Image.h"

#include "rhi/Device.h"

#include <glm/vec4.hpp>

namespace lpv::test {

// 64x64: two indexed triangles at different depths into RGBA8 + RGBA16F targets and D32F depth.
struct MrtImages {
    Image color;
    Image second;
    Image depth;
};
MrtImages renderIndexedMrt(rhi::Device& device);
inline constexpr glm::vec4 kMrtClear{0.0f, 0.0f, 0.2f, 1.0f};
inline constexpr glm::vec4 kMrtTint{0.25f, 0.5f, 0.75f, 1.0f};

// 32^3 RGBA16F storage image written by a compute shader.
inline constexpr uint32_t kVolumeSize = 32;
Image fillVolume(rhi::Device& device);
glm::vec4 expectedVolumeTexel(uint32_t x, uint32_t y, uint32_t z);

// 16x16 RGBA16F cleared to kBlendClear, then kBlendColor added twice.
inline constexpr glm::vec4 kBlendClear{0.1f, 0.0f, 0.0f, 0.0f};
inline constexpr glm::vec4 kBlendColor{0.25f, 0.5f, 0.125f, 0.25f};
Image additiveBlend(rhi::Device& device);

// 16x16 RGBA16F cleared to 0, then kPointCount points from vertex kFirstPoint on (tests/shaders/
// points.vert: every third one outside the clip volume) each add kBlendColor to their pixel: more
// points than one draw of a CPU device's split point lists holds, with a remainder.
inline constexpr uint32_t kPointCount = 3001;
inline constexpr uint32_t kFirstPoint = 100;
Image drawPoints(rhi::Device& device);
glm::vec4 expectedPointTexel(uint32_t x, uint32_t y);

// 4^3 RGBA16F volume cleared to 0, then kLayeredPointCount points (tests/shaders/layered_points.vert:
// each picks its own slice with gl_Layer, every fifth is outside the clip volume) add kBlendColor
// to their texel in one layered draw.
inline constexpr uint32_t kLayeredSize = 4;
inline constexpr uint32_t kLayeredPointCount = 200;
Image drawLayeredPoints(rhi::Device& device);
glm::vec4 expectedLayeredTexel(uint32_t x, uint32_t y, uint32_t z);

// 16x4 RGBA16F cleared to 0: four quads of 4x4 texels, quad q over columns 4q..4q+3, each drawn
// with the value its first instance picks from a per-instance stream (kMultiDrawValues) as red.
// One drawIndexedIndirect of kMultiDraws (quad, first instance) draws three; quad 1 stays clear.
inline constexpr uint32_t kMultiDrawValues[4] = {7, 11, 13, 17};
inline constexpr uint32_t kMultiDraws[3][2] = {{0, 2}, {2, 0}, {3, 3}};
struct MultiDrawResult {
    Image image;
    rhi::CommandCounts counts; // the frame's
};
MultiDrawResult multiDrawQuads(rhi::Device& device);

// 16x16 RGBA16F cleared to 0 with a D32FS8 target whose stencil is cleared to kStencilClear. A
// fragment shader exports each pixel's stencil (tests/shaders/stencil_export.frag: x & 3 in bits
// 0-1, y & 3 in bits 4-5; columns 12-15 keep the clear); then three fullscreen draws add
// kStencilColors[i] where the stencil, masked by kStencilMasks[i], equals kStencilRefs[i].
inline constexpr uint8_t kStencilClear = 0x13;
inline constexpr uint8_t kStencilMasks[3] = {0x03, 0x30, 0xff};
inline constexpr uint8_t kStencilRefs[3] = {0x02, 0x10, 0x13};
inline constexpr glm::vec4 kStencilColors[3] = {
    {0.25f, 0.0f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.125f, 1.0f}};
Image drawStencilFields(rhi::Device& device);
glm::vec4 expectedStencilTexel(uint32_t x, uint32_t y);

// 8^3 RGBA16F volume: slice kInjectSlice receives kBlendColor twice (additive) through a render
// pass, then a compute shader reads the whole volume through a sampler into a storage buffer.
inline constexpr uint32_t kInjectSize = 8;
inline constexpr uint32_t kInjectSlice = 3;
struct InjectionResult {
    Image readback;                      // readTexture of the volume
    std::vector<glm::vec4> sampledReads; // what the compute shader sampled, in the same order
};
InjectionResult injectIntoSlice(rhi::Device& device);

} // namespace lpv::test
