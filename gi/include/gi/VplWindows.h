// The sun's gather VPLs of a cascade that each of the gather's windows can take, listed per phase
// (vpl_windows.comp), so that a texel of the per-pixel gather (VplGather) walks the lit VPLs its
// window takes rather than the whole cluster grid: the coarser cascades' maps reach far past the
// scene, and most of their slots are unlit or in a finer cascade's box.
//
// A texel whose finest cascade is this one takes window 0: the VPLs within the cascade's box (any
// where it is the coarsest gathered); one in a finer cascade's box, window 1: those also outside
// the next finer box (vpl_gather.frag's Window). The lists only narrow what the gather walks: it
// tests every VPL it reads as before and sums them in the grid's order.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <cstdint>
#include <optional>

namespace lpv::gi {

// The per-pixel gather's 4 x 4 interleave (vpl_gather.frag): texel phase (x, y) sums the lists of
// phase x + 4 y, the sun's VPLs by window here and the listed faces (GatheredReflection).
inline constexpr uint32_t kGatherPhases = 16;

class VplWindows {
public:
    static constexpr uint32_t kWindows = 2;
    static constexpr uint32_t kPhases = kGatherPhases;

    // The slots one phase's list may hold, of a cluster grid `side` across (two slots a cluster).
    static uint32_t room(uint32_t side) { return 2 * ((side + 3) / 4) * ((side + 3) / 4); }
    // A lists buffer's bytes: the counts, then kWindows x kPhases lists of room(side) slots.
    static constexpr uint64_t kCountBytes = uint64_t(kWindows) * kPhases * 4;
    static uint64_t bytes(uint32_t side) {
        return kCountBytes + uint64_t(kWindows) * kPhases * room(side) * 4;
    }

    explicit VplWindows(rhi::Device& device);
    ~VplWindows();
    VplWindows(const VplWindows&) = delete;
    VplWindows& operator=(const VplWindows&) = delete;

    // Lists, into `lists` (bytes(side)), the lit VPLs of `vpls` (a cluster grid `side` across) that
    // lie within `within` (none: anywhere) and, for window 1, outside `beyond` (none: window 1
    // takes none).
    void record(rhi::CommandList& cmd, rhi::BufferHandle vpls, uint32_t side,
                std::optional<VolumeGrid> within, std::optional<VolumeGrid> beyond, rhi::BufferHandle lists);

private:
    rhi::Device& device_;
    rhi::ComputePipelineHandle pipeline_;
};

// One cascade's windows: each window reads every slot (48 bytes) and writes the slots it takes
// (4 bytes each, at most all).
engine::WorkCounts vplWindowsWork(uint32_t side);

} // namespace lpv::gi
