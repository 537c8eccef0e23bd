// Timestamp query pools per frame slot, read back without waiting.
#include "VkTimestamps.h"

#include "VkCheck.h"

#include <algorithm>
#include <string>

namespace lpv::rhi::vk {

void TimestampRing::create(const VulkanContext& ctx, bool enabled, uint32_t sets, uint32_t perFrame) {
    enabled_ = enabled && perFrame > 0;
    perFrame_ = perFrame;
    period_ = ctx.properties.limits.timestampPeriod;
    validMask_ = ctx.timestampValidBits >= 64 ? ~0ull : ((1ull << ctx.timestampValidBits) - 1);
    if (!enabled_) return;
    sets_.resize(sets);
    for (uint32_t i = 0; i < sets; ++i) {
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = perFrame;
        vkCheck(vkCreateQueryPool(ctx.device, &info, nullptr, &sets_[i].pool), "vkCreateQueryPool");
        sets_[i].written.assign(perFrame, 0);
        ctx.name(VK_OBJECT_TYPE_QUERY_POOL, sets_[i].pool, "timestamps slot " + std::to_string(i));
    }
}

void TimestampRing::destroy(VkDevice device) {
    for (Set& s : sets_)
        if (s.pool) vkDestroyQueryPool(device, s.pool, nullptr);
    sets_.clear();
}

void TimestampRing::beginFrame(VkCommandBuffer cmd, uint64_t frame) {
    if (!enabled_) return;
    Set& s = setFor(frame);
    s.frame = frame;
    std::fill(s.written.begin(), s.written.end(), uint8_t(0));
    vkCmdResetQueryPool(cmd, s.pool, 0, perFrame_);
}

void TimestampRing::write(VkCommandBuffer cmd, uint64_t frame, uint32_t slot) {
    if (slot >= perFrame_)
        throw Error("timestamp slot " + std::to_string(slot) + " >= maxTimestampsPerFrame " +
                    std::to_string(perFrame_));
    if (!enabled_) return;
    Set& s = setFor(frame);
    // A query can be written once per reset; a second write would be undefined in Vulkan.
    if (s.written[slot])
        throw Error("timestamp slot " + std::to_string(slot) + " written twice in one frame");
    s.written[slot] = 1;
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, s.pool, slot);
}

bool TimestampRing::read(VkDevice device, uint64_t frame, uint64_t lastSubmitted, std::span<uint64_t> out) {
    if (out.size() > perFrame_) throw Error("readTimestamps: more slots than maxTimestampsPerFrame");
    if (!enabled_ || frame == 0 || frame > lastSubmitted) return false;
    Set& s = setFor(frame);
    if (s.frame != frame) return false;
    for (size_t i = 0; i < out.size(); ++i) {
        if (!s.written[i]) {
            out[i] = 0;
            continue;
        }
        uint64_t ticks = 0;
        const VkResult r = vkGetQueryPoolResults(device, s.pool, uint32_t(i), 1, sizeof(ticks), &ticks,
                                                 sizeof(ticks), VK_QUERY_RESULT_64_BIT);
        if (r == VK_NOT_READY) return false;
        vkCheck(r, "vkGetQueryPoolResults");
        out[i] = uint64_t(double(ticks & validMask_) * period_);
    }
    return true;
}

} // namespace lpv::rhi::vk
