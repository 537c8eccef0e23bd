// Bookkeeping of live GPU allocations by category, current and peak.
#include "rhi/AllocationRecord.h"

#include <algorithm>

namespace lpv::rhi {

void AllocationRecord::add(ResourceType type, uint32_t handleBits, Allocation allocation) {
    CategoryUsage& cat = categories_[allocation.category];
    cat.currentBytes += allocation.bytes;
    cat.peakBytes = std::max(cat.peakBytes, cat.currentBytes);
    cat.count += 1;
    total_ += allocation.bytes;
    peakTotal_ = std::max(peakTotal_, total_);
    live_[key(type, handleBits)] = std::move(allocation);
}

void AllocationRecord::remove(ResourceType type, uint32_t handleBits) {
    auto it = live_.find(key(type, handleBits));
    if (it == live_.end()) return;
    CategoryUsage& cat = categories_[it->second.category];
    cat.currentBytes -= it->second.bytes;
    cat.count -= 1;
    total_ -= it->second.bytes;
    live_.erase(it);
}

uint64_t AllocationRecord::bytesIn(const std::string& prefix) const {
    uint64_t sum = 0;
    for (const auto& [name, usage] : categories_) {
        const bool match = name == prefix || (name.size() > prefix.size() && name.starts_with(prefix) &&
                                              name[prefix.size()] == '.');
        if (match) sum += usage.currentBytes;
    }
    return sum;
}

std::vector<Allocation> AllocationRecord::live() const {
    std::vector<Allocation> out;
    out.reserve(live_.size());
    for (const auto& [k, a] : live_)
        out.push_back(a);
    return out;
}

} // namespace lpv::rhi
