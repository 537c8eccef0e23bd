// The GI settings' derived sizes and cross-checks.
#include "gi/LpvSettings.h"

#include <cmath>
#include <string>

namespace lpv::gi {
namespace {

// The valid gi.vpl_count nearest `wanted` (a square whose side divides rsmSize, within the
// setting's range; the smaller on a tie), for the error that refuses `wanted`; 0 when there is none.
uint32_t nearestVplCount(uint32_t wanted, uint32_t rsmSize, uint32_t least, uint32_t most) {
    uint64_t best = 0, bestDistance = ~uint64_t(0);
    for (uint32_t side = 1; side <= rsmSize; ++side) {
        const uint64_t count = uint64_t(side) * side;
        if (rsmSize % side != 0 || count < uint64_t(least) || count > uint64_t(most)) continue;
        const uint64_t distance = count > wanted ? count - wanted : wanted - count;
        if (distance < bestDistance) best = count, bestDistance = distance;
    }
    return uint32_t(best);
}

} // namespace

uint32_t LpvSettings::vplSlots() const {
    return vplCount * kVplsPerCluster;
}

uint32_t LpvSettings::vplGridSide() const {
    return uint32_t(std::lround(std::sqrt(double(vplCount))));
}

std::optional<LpvSettingsError> validateLpvSettings(const LpvSettings& s) {
    const uint32_t side = s.vplGridSide();
    if (side * side != s.vplCount || s.rsmSize % side != 0) {
        const uint32_t nearest = nearestVplCount(s.vplCount, s.rsmSize, kMinVplCount, kMaxVplCount);
        return LpvSettingsError{
            "gi.vpl_count", "gi.rsm_size",
            "'gi.vpl_count' = " + std::to_string(s.vplCount) +
                ": expected a square number whose side divides gi.rsm_size (" + std::to_string(s.rsmSize) +
                ")" +
                (nearest ? ", such as " + std::to_string(nearest)
                         : ", and none from " + std::to_string(kMinVplCount) + " to " +
                               std::to_string(kMaxVplCount) +
                               " is: choose a gi.rsm_size with more divisors, such as a power of two")};
    }
    // Only a slice someone chose: without one, the last slice of a small volume is shown.
    if (s.debugSlice && *s.debugSlice >= s.gridSize)
        return LpvSettingsError{"gi.debug_slice", "gi.grid_size",
                                "'gi.debug_slice' = " + std::to_string(*s.debugSlice) +
                                    ": outside the volume: gi.grid_size is " + std::to_string(s.gridSize) +
                                    ", so expected 0 to " + std::to_string(s.gridSize - 1)};
    if (s.bounces > 1 && !s.occlusion)
        return LpvSettingsError{"gi.bounces", "gi.occlusion",
                                "'gi.bounces' = " + std::to_string(s.bounces) +
                                    ": expected 1 while gi.occlusion is false (further bounces reflect the "
                                    "light the geometry volume blocks)"};
    return std::nullopt;
}

std::string_view shFormatName(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return "rgba8";
    case ShFormat::Rgba16f:
        return "rgba16f";
    case ShFormat::Rgba32f:
        return "rgba32f";
    }
    return "?";
}

rhi::Format shTextureFormat(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return rhi::Format::RGBA8Unorm;
    case ShFormat::Rgba16f:
        return rhi::Format::RGBA16F;
    case ShFormat::Rgba32f:
        return rhi::Format::RGBA32F;
    }
    return rhi::Format::RGBA16F;
}

} // namespace lpv::gi
