// Windowed statistics of profiler samples.
#include "engine/profiler/SampleWindow.h"

#include <algorithm>
#include <cmath>

namespace lpv::engine {

void SampleWindow::add(double value) {
    samples_[next_] = value;
    next_ = (next_ + 1) % uint32_t(samples_.size());
    count_ = std::min<uint32_t>(count_ + 1, uint32_t(samples_.size()));
    last_ = value;
}

SampleStats SampleWindow::stats() const {
    SampleStats s;
    s.count = count_;
    if (count_ == 0) return s;
    // The window's samples are the first count_ entries until it wraps, then all of them.
    std::copy_n(samples_.begin(), count_, scratch_.begin());
    std::sort(scratch_.begin(), scratch_.begin() + count_);
    double sum = 0;
    for (uint32_t i = 0; i < count_; ++i)
        sum += scratch_[i];
    s.last = last_;
    s.mean = sum / count_;
    s.median = count_ % 2 ? scratch_[count_ / 2] : 0.5 * (scratch_[count_ / 2 - 1] + scratch_[count_ / 2]);
    // Nearest-rank percentile.
    const uint32_t rank = uint32_t(std::ceil(0.95 * count_));
    s.p95 = scratch_[std::max<uint32_t>(rank, 1) - 1];
    s.max = scratch_[count_ - 1];
    return s;
}

} // namespace lpv::engine
