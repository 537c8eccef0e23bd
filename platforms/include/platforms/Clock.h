// Monotonic time for frame pacing and CPU profiling scopes.
#pragma once

#include <chrono>
#include <cstdint>

namespace lpv::platforms {

inline uint64_t nowNanoseconds() {
    return uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(
                        std::chrono::steady_clock::now().time_since_epoch())
                        .count());
}

} // namespace lpv::platforms
