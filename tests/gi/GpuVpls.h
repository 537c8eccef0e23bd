// VPLs as the GPU passes read them (std430 {vec4 position (w: > 0 lit; the cluster pass packs its
// patch there, patch_form_factor.glsl), vec4 normal (w: its share of its RSM block's area), vec4
// flux}), for tests that inject their own (position.w 1: a point, without a patch).
#pragma once

#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <glm/vec4.hpp>

#include <vector>

namespace lpv::test {

struct GpuVpl {
    glm::vec4 position, normal, flux;
};

// `vpls` in the GPU layout, in a storage buffer (the caller destroys it).
inline rhi::BufferHandle uploadVpls(rhi::Device& device, const std::vector<gi::Vpl>& vpls) {
    std::vector<GpuVpl> gpu;
    for (const gi::Vpl& v : vpls)
        gpu.push_back({glm::vec4(v.position, 1), glm::vec4(v.normal, 1), glm::vec4(v.flux, 0)});
    return device.createBuffer({gpu.size() * sizeof(GpuVpl), rhi::kBufferStorage | rhi::kBufferTransfer,
                                rhi::MemoryAccess::GpuOnly, "test vpls", "test"},
                               gpu.data());
}

} // namespace lpv::test
