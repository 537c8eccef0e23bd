// Every GPU allocation the device made, with its size, category and debug name. The frame
// profiler sums it by category against the platform's memory budget; a leak shows up as an
// entry that outlives its owner.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace lpv::rhi {

enum class ResourceType : uint8_t { Buffer, Texture };

struct Allocation {
    ResourceType type = ResourceType::Buffer;
    std::string name;
    std::string category;
    uint64_t bytes = 0;
};

struct CategoryUsage {
    uint64_t currentBytes = 0;
    uint64_t peakBytes = 0;
    uint32_t count = 0;
};

class AllocationRecord {
public:
    void add(ResourceType type, uint32_t handleBits, Allocation allocation);
    void remove(ResourceType type, uint32_t handleBits);

    uint64_t totalBytes() const { return total_; }
    uint64_t peakTotalBytes() const { return peakTotal_; }
    // Categories match by prefix: "gi" sums "gi.lpv", "gi.gv" and "gi.rsm".
    uint64_t bytesIn(const std::string& categoryPrefix) const;
    const std::map<std::string, CategoryUsage>& categories() const { return categories_; }
    std::vector<Allocation> live() const;

private:
    static uint64_t key(ResourceType type, uint32_t bits) { return (uint64_t(type) << 32) | bits; }

    std::map<uint64_t, Allocation> live_;
    std::map<std::string, CategoryUsage> categories_;
    uint64_t total_ = 0;
    uint64_t peakTotal_ = 0;
};

} // namespace lpv::rhi
