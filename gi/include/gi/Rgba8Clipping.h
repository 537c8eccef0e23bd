// Whether RGBA8 volumes clip: light beyond gi.rgba8_range is cut off at it and lost. The shaders
// that encode a cascade's result note the largest coefficient they met over the range
// (rgba8_clipping.glsl) in a small buffer the CPU reads framesInFlight frames later, without
// waiting (rhi MemoryAccess::HostRead). LightPropagationVolume turns it into a warning and a
// profiler note that name the range to set.
//
// A development check: it costs a comparison per encoded cell and the buffer below, which its
// memory category ("debug.rgba8_clipping") keeps out of the GI memory budget, as a console's
// shipping build would leave the check out.
#pragma once

#include "rhi/Device.h"

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

namespace lpv::gi {

// The profiler notes' topic for clipping found (LightPropagationVolume).
inline constexpr std::string_view kRgba8ClippingNoteTopic = "GI RGBA8 clipping";

// The peak (light over the range, as a multiple of it) from which LightPropagationVolume reports
// clipping. A few of the brightest cells a little over lose little, and a larger range rounds
// every dim cell more coarsely: at the default range (12) the Cornell box read 1.32x (320x240) with its mean
// indirect light 0.8% under RGBA16F's, and range 20, which does not clip, was worse per pixel
// (6.9% against 5.4% of the mean; the atrium 9.5% against 6.1%). Clipped light no longer
// propagates, so the loss grows fast beyond: the Cornell box read 1.43x at range 10 with its
// light 2.5% under, 1.57x at 8 with 13% under; the atrium 1.56x at 8, 0.6% under, and 1.85x at 6,
// 5% under (640x360, Vulkan; the per-pixel figures with the PC settings, 0.2 m cells).
inline constexpr float kReportedClipping = 1.5f;

// The gi.rgba8_range that would hold light `peak` times the range `range`, with a quarter to spare
// (the peak was measured in volumes already clipped, so it can read low), rounded up to two
// significant digits.
float rangeToHold(float range, float peak);

class Rgba8Clipping {
public:
    static constexpr uint32_t kBinding = 23; // rgba8_clipping.glsl
    static constexpr uint32_t kCascades = 4; // gi.cascades at most

    explicit Rgba8Clipping(rhi::Device& device);
    ~Rgba8Clipping();
    Rgba8Clipping(const Rgba8Clipping&) = delete;
    Rgba8Clipping& operator=(const Rgba8Clipping&) = delete;

    // Binds cascade `cascade`'s record for the frame being recorded at kBinding. The first bind of
    // a frame first takes in what this frame's record held: the frame framesInFlight ago, which
    // beginFrame() waited for.
    void bind(rhi::CommandList& cmd, uint32_t cascade);

    // At the end of a run, once the device is idle: takes in the oldest frame's record not taken
    // in yet and returns true, or returns false when none is left (a run shorter than
    // framesInFlight frames would otherwise read none). Called until false, with a look at peaks()
    // after each, as while running.
    bool takeInNextFinished();

    // For each cascade, what the last finished frame that encoded it met: its largest coefficient
    // as a multiple of its range, 0 when nothing was over. Kept until that cascade is encoded again
    // (a coarse cascade kept between updates keeps its value).
    const std::array<float, kCascades>& peaks() const { return peaks_; }
    // The frame each peak is from (0: none finished yet).
    const std::array<uint64_t, kCascades>& peakFrames() const { return peakFrames_; }

private:
    void takeIn(uint64_t frame);
    void takeInRegion(uint32_t region);

    rhi::Device& device_;
    uint32_t regions_; // one per frame in flight
    rhi::BufferHandle buffer_;
    uint32_t* mapped_ = nullptr;
    uint64_t frame_ = 0; // the frame whose region bind() fills
    // Per region: the frame that last wrote it and the cascades it bound.
    std::vector<uint64_t> regionFrame_;
    std::vector<uint32_t> regionCascades_;
    std::vector<uint8_t> regionTaken_; // its record has been taken in since it was written
    std::array<float, kCascades> peaks_{};
    std::array<uint64_t, kCascades> peakFrames_{};
};

} // namespace lpv::gi
