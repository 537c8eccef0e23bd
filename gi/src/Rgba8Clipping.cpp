// RGBA8 clipping records, read back without waiting (gi/Rgba8Clipping.h).
#include "gi/Rgba8Clipping.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

namespace lpv::gi {
namespace {

// Each cascade's record sits at its own offset, which every device's storage-buffer offset
// alignment allows (Vulkan's limit is at most 256).
constexpr uint64_t kRecordBytes = 256;

} // namespace

float rangeToHold(float range, float peak) {
    const double wanted = double(range) * double(std::max(peak, 1.0f)) * 1.25;
    const double step = std::pow(10.0, std::floor(std::log10(wanted)) - 1.0);
    return float(std::ceil(wanted / step - 1e-9) * step);
}

Rgba8Clipping::Rgba8Clipping(rhi::Device& device)
    : device_(device), regions_(std::max(1u, device.caps().framesInFlight)), regionFrame_(regions_, 0),
      regionCascades_(regions_, 0), regionTaken_(regions_, 0) {
    buffer_ =
        device.createBuffer({kRecordBytes * kCascades * regions_, rhi::kBufferStorage,
                             rhi::MemoryAccess::HostRead, "lpv rgba8 clipping", "debug.rgba8_clipping"});
    mapped_ = static_cast<uint32_t*>(device.mapped(buffer_));
    for (uint32_t i = 0; i < kCascades * regions_; ++i)
        mapped_[i * kRecordBytes / sizeof(uint32_t)] = 0;
}

Rgba8Clipping::~Rgba8Clipping() {
    device_.waitIdle();
    device_.destroy(buffer_);
}

static uint32_t* recordAt(uint32_t* mapped, uint32_t region, uint32_t cascade) {
    return mapped + (uint64_t(region) * Rgba8Clipping::kCascades + cascade) * kRecordBytes / sizeof(uint32_t);
}

// A frame that recorded nothing (GI off) leaves a region to be read later than a newer one: a
// cascade keeps the newest frame's peak.
void Rgba8Clipping::takeInRegion(uint32_t region) {
    const uint64_t written = regionFrame_[region];
    for (uint32_t c = 0; c < kCascades; ++c) {
        if (written == 0 || !(regionCascades_[region] & (1u << c)) || written <= peakFrames_[c]) continue;
        peaks_[c] = std::bit_cast<float>(*recordAt(mapped_, region, c));
        peakFrames_[c] = written;
    }
    regionTaken_[region] = 1;
}

void Rgba8Clipping::takeIn(uint64_t frame) {
    frame_ = frame;
    const uint32_t region = uint32_t(frame % regions_);
    // Written framesInFlight or more frames ago: finished, since beginFrame() of this frame waited.
    takeInRegion(region);
    for (uint32_t c = 0; c < kCascades; ++c)
        *recordAt(mapped_, region, c) = 0;
    regionFrame_[region] = frame;
    regionCascades_[region] = 0;
    regionTaken_[region] = 0;
}

bool Rgba8Clipping::takeInNextFinished() {
    uint32_t oldest = regions_;
    for (uint32_t region = 0; region < regions_; ++region)
        if (regionFrame_[region] != 0 && !regionTaken_[region] &&
            (oldest == regions_ || regionFrame_[region] < regionFrame_[oldest]))
            oldest = region;
    if (oldest == regions_) return false;
    takeInRegion(oldest);
    return true;
}

void Rgba8Clipping::bind(rhi::CommandList& cmd, uint32_t cascade) {
    if (cascade >= kCascades) throw std::logic_error("gi: rgba8 clipping record for cascade out of range");
    const uint64_t frame = device_.frameIndex();
    if (frame != frame_) takeIn(frame);
    const uint32_t region = uint32_t(frame % regions_);
    regionCascades_[region] |= 1u << cascade;
    cmd.bindStorageBuffer(kBinding, buffer_, (uint64_t(region) * kCascades + cascade) * kRecordBytes,
                          kRecordBytes);
}

} // namespace lpv::gi
