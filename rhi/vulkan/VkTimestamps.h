// GPU timestamps: one query pool per frame slot, framesInFlight + 1 slots, so a frame's results stay
// readable for framesInFlight + 1 frames after it was recorded. Reading never waits.
#pragma once

#include "VkContext.h"

#include <cstdint>
#include <span>
#include <vector>

namespace lpv::rhi::vk {

class TimestampRing {
public:
    // `enabled` false (no timestamp support) turns every call into a no-op.
    void create(const VulkanContext& ctx, bool enabled, uint32_t sets, uint32_t perFrame);
    void destroy(VkDevice device);
    bool enabled() const { return enabled_; }

    // Claims frame `frame`'s pool and resets it on the GPU (outside any rendering instance).
    void beginFrame(VkCommandBuffer cmd, uint64_t frame);
    void write(VkCommandBuffer cmd, uint64_t frame, uint32_t slot);
    // Fills nanoseconds for the slots written in `frame` (0 for the others). False when `frame`'s
    // pool was reused, it is not yet submitted (`lastSubmitted`), or the GPU has not finished it.
    bool read(VkDevice device, uint64_t frame, uint64_t lastSubmitted, std::span<uint64_t> out);

private:
    struct Set {
        VkQueryPool pool = VK_NULL_HANDLE;
        uint64_t frame = 0;
        std::vector<uint8_t> written;
    };
    Set& setFor(uint64_t frame) { return sets_[frame % sets_.size()]; }

    std::vector<Set> sets_;
    uint32_t perFrame_ = 0;
    double period_ = 1.0;
    uint64_t validMask_ = ~0ull;
    bool enabled_ = false;
};

} // namespace lpv::rhi::vk
