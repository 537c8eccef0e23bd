// The last N samples of one figure (a pass's milliseconds), with last, mean, median, 95th
// percentile and max over them. Storage is fixed at construction; statistics sort into a scratch
// buffer owned by the window, so a frame that asks for them allocates nothing.
#pragma once

#include <cstdint>
#include <vector>

namespace lpv::engine {

struct SampleStats {
    uint32_t count = 0;
    double last = 0, mean = 0, median = 0, p95 = 0, max = 0;
};

class SampleWindow {
public:
    explicit SampleWindow(uint32_t capacity = 120) : samples_(capacity), scratch_(capacity) {}
    void add(double value);
    SampleStats stats() const;
    uint32_t count() const { return count_; }

private:
    std::vector<double> samples_;
    mutable std::vector<double> scratch_;
    uint32_t next_ = 0;
    uint32_t count_ = 0;
    double last_ = 0;
};

} // namespace lpv::engine
