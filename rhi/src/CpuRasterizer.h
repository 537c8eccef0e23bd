// Facts about CPU rasterizers (Mesa's lavapipe and llvmpipe) that shape how work is dispatched.
#pragma once

#include <cstdint>
#include <string_view>

namespace lpv::rhi {

// True for a renderer string of a CPU rasterizer.
bool isCpuRasterizer(std::string_view renderer);

// Workgroups a CPU rasterizer runs at once: one per worker thread, which Mesa sizes from
// LP_NUM_THREADS or else the host's hardware threads.
uint32_t cpuRasterizerThreads();

} // namespace lpv::rhi
