#include "CpuRasterizer.h"

#include <cstdlib>
#include <thread>

namespace lpv::rhi {

bool isCpuRasterizer(std::string_view renderer) {
    return renderer.find("llvmpipe") != std::string_view::npos ||
           renderer.find("softpipe") != std::string_view::npos ||
           renderer.find("SwiftShader") != std::string_view::npos;
}

uint32_t cpuRasterizerThreads() {
    if (const char* v = std::getenv("LP_NUM_THREADS")) {
        const long n = std::strtol(v, nullptr, 10);
        if (n > 0) return uint32_t(n);
    }
    const unsigned n = std::thread::hardware_concurrency();
    return n > 0 ? n : 1;
}

} // namespace lpv::rhi
