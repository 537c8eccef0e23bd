// The light propagation volume's resources, which LpvInjection and LpvPropagation record into: the
// injection volume the VPLs are added into (float), the partial sums propagation ping-pongs between
// (packed; with several cascades with a one-cell shell of what lies beyond the border) and the
// accumulated result in gi.sh_format. The injection volume and the partial sums are scratch that
// every cascade shares; each cascade keeps a result of its own (createResult).
#pragma once

#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "gi/Rgba8Clipping.h"
#include "rhi/Device.h"

#include <array>
#include <memory>
#include <string>

namespace lpv::gi {

// Between iterations propagation keeps a cell's 12 coefficients in 1 RGBA32UI texel (rgba8,
// as 10-bit codes), 3 RGBA16F texels (rgba16f, one per channel) or 3 RGBA32UI texels (rgba32f, the floats'
// bits): see propagate_body.glsl.
uint32_t packedTexelCount(ShFormat f);
rhi::Format packedTexelFormat(ShFormat f, uint32_t texel);
// Whether the partial sums carry a one-cell shell of what lies beyond the border: where a coarser
// cascade hands its light in (gi.cascades > 1). Reading the handoff from a shell is 2-3x faster on
// a CPU rasterizer than choosing it per load, but the shell costs memory, and a single cascade
// (the Xbox 360 budget holds one) only ever reads a zero there.
bool partialSumShell(const LpvSettings& s);
// Cells per axis of a partial-sum volume: n, or with the shell n + 2 and for an odd n one more
// layer for the 2x2 columns that stick out.
uint32_t partialSumSize(const LpvSettings& s);

class LpvVolumes {
public:
    // `partialSums` false: without partial sums, for a propagation that keeps them
    // (LpvPropagation::stacked()).
    LpvVolumes(rhi::Device& device, const LpvSettings& settings, bool partialSums = true);
    ~LpvVolumes();
    LpvVolumes(const LpvVolumes&) = delete;
    LpvVolumes& operator=(const LpvVolumes&) = delete;

    // True when these volumes were made for the sizes, format and partial-sum layout of `settings`.
    bool matches(const LpvSettings& settings) const;

    // A further set of result volumes (3 SH textures in gi.sh_format, sampled by the lookup).
    std::array<rhi::TextureHandle, 3> createResult(const std::string& name) const;

    const std::array<rhi::TextureHandle, 3>& injected() const { return inject_; }
    const std::array<rhi::TextureHandle, 3>& accumulated() const { return accum_; }
    // The partial sums, ping and pong: packedTexelCount textures each (the others null),
    // partialSumSize^3; all null where made without.
    const std::array<std::array<rhi::TextureHandle, 3>, 2>& partialSums() const { return partial_; }
    bool encoded() const { return settings_.shFormat == ShFormat::Rgba8; }
    // The largest coefficient an rgba8 volume placed at `grid` stores (ShEncoding.h):
    // gi.rgba8_range is a radiance (intensity over a cell's cross-section, what the lookup shows),
    // so the range in a volume's intensities grows with its cells' area. A coarse cascade, whose
    // cells are 4x and 16x the finest's area, then clips no sooner than the finest, and the finest
    // keeps its steps small.
    float encodeRange(const VolumeGrid& grid) const {
        return settings_.rgba8Range * grid.cellSize * grid.cellSize;
    }
    // What the injection volume holds now (LpvInjection): the light of cascade `cascade`, placed at
    // `grid`. Propagation and the bounces encode in that grid's range and note clipping for that
    // cascade.
    void setInjected(const VolumeGrid& grid, uint32_t cascade) {
        injectedRange_ = encodeRange(grid);
        injectedCascade_ = cascade;
    }
    // The range of the volume last injected, in which propagation and the bounces encode; 0 before
    // the first injection.
    float injectedEncodeRange() const { return injectedRange_; }
    // The cascade last injected.
    uint32_t injectedCascade() const { return injectedCascade_; }
    // rgba8: where encodes note light over the range; null for the float formats, which do not clip.
    Rgba8Clipping* clipping() { return clipping_.get(); }
    const Rgba8Clipping* clipping() const { return clipping_.get(); }
    uint32_t gridSize() const { return settings_.gridSize; }

private:
    rhi::Device& device_;
    LpvSettings settings_;
    float injectedRange_ = 0.0f; // encodeRange of the grid last injected
    uint32_t injectedCascade_ = 0;
    std::unique_ptr<Rgba8Clipping> clipping_; // rgba8 only
    std::array<rhi::TextureHandle, 3> inject_, accum_;
    // Partial sums between iterations, ping and pong, packed (packedTexelCount texels per cell).
    std::array<std::array<rhi::TextureHandle, 3>, 2> partial_{};
};

} // namespace lpv::gi
