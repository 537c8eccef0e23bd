// The light propagation volume itself: injection of VPLs into a float volume (points drawn per
// slice with additive blending), then N propagation iterations whose partial sums ping-pong
// between two packed volumes (with several cascades: with a shell of what lies beyond the border),
// the last writing the accumulated volume in gi.sh_format. Three SH textures (R, G, B) for the injection and
// the accumulation.
#pragma once

#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "gi/Rgba8Clipping.h"
#include "rhi/Device.h"

#include <glm/vec4.hpp>

#include <array>
#include <memory>
#include <span>
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

// Cells per propagation thread along z for an n^3 volume: a CPU rasterizer runs one workgroup per
// host thread and pays for every fetch, so there each thread walks a long column (its z
// neighbours then come from registers) with just enough workgroups to keep every thread busy; a
// GPU (concurrentWorkgroups 0) wants many short ones.
uint32_t propagationColumnLength(uint32_t n, uint32_t concurrentWorkgroups);

// Light from beyond a cascade's border: the next coarser cascade's result and both placements.
struct CascadeHandoff {
    std::array<rhi::TextureHandle, 3> coarse;
    VolumeGrid coarseGrid, fineGrid;
};

// One light's VPLs for inject(): a buffer of std430 {vec4 position (w: valid), vec4 normal,
// vec4 flux} and where its light is, for the half-cell shift toward it.
struct VplSource {
    rhi::BufferHandle vpls;
    uint32_t count = 0;
    // w 0: xyz is the direction a distant light travels (the sun); w 1: xyz is the position of a
    // light at a point (a spot or point light), each VPL's direction then runs from it.
    glm::vec4 light{0.0f, -1.0f, 0.0f, 0.0f};
};

class LpvVolumes {
public:
    // `columnLength`: cells each propagation thread walks along z; 0 picks it from the device
    // (propagationColumnLength). Tests pin it to cover the shapes other devices get.
    LpvVolumes(rhi::Device& device, const LpvSettings& settings, uint32_t columnLength = 0);
    ~LpvVolumes();
    LpvVolumes(const LpvVolumes&) = delete;
    LpvVolumes& operator=(const LpvVolumes&) = delete;

    // True when these volumes were made for the sizes, format and partial-sum layout of `settings`.
    bool matches(const LpvSettings& settings) const;

    // Clears the injection volume and adds `vplCount` VPLs from `vpls` (std430 array of
    // {vec4 position (w: valid), vec4 normal, vec4 flux}).
    void inject(rhi::CommandList& cmd, rhi::BufferHandle vpls, uint32_t vplCount, const VolumeGrid& grid,
                glm::vec3 lightDirection, float intensity);
    // Clears the injection volume and adds the VPLs of every source (several lights share the
    // volume), all in one pass per slice. `cascade`: whose record (Rgba8Clipping) the rgba8
    // encodes of what is propagated from this injection note clipping in.
    void inject(rhi::CommandList& cmd, std::span<const VplSource> sources, const VolumeGrid& grid,
                float intensity, uint32_t cascade = 0);
    // Propagates `iterations` (>= 1) times from the injection volume, in the units of the grid last
    // injected (rgba8: injectedEncodeRange(); std::logic_error before any inject()); accumulated() then holds
    // the injected volume plus every iteration's propagated light. With `faceTransmittance` (GeometryVolume),
    // the flux through every face is attenuated by it. `result`: where the last iteration writes (a set from
    // createResult(), e.g. another cascade's); accumulated() when null. `handoff`: outside the volume,
    // neighbours read the coarser cascade's result (in this volume's units) instead of nothing; only for
    // volumes with a shell (partialSumShell), std::logic_error otherwise.
    void propagate(rhi::CommandList& cmd, uint32_t iterations, rhi::TextureHandle faceTransmittance = {},
                   const std::array<rhi::TextureHandle, 3>* result = nullptr,
                   const CascadeHandoff* handoff = nullptr);
    // A further set of result volumes (3 SH textures in gi.sh_format, sampled by the lookup).
    // The injection and partial-sum volumes are scratch, shared by every cascade; results persist.
    std::array<rhi::TextureHandle, 3> createResult(const std::string& name) const;

    const std::array<rhi::TextureHandle, 3>& injected() const { return inject_; }
    const std::array<rhi::TextureHandle, 3>& accumulated() const { return accum_; }
    bool encoded() const { return settings_.shFormat == ShFormat::Rgba8; }
    // The largest coefficient an rgba8 volume placed at `grid` stores (ShEncoding.h):
    // gi.rgba8_range is a radiance (intensity over a cell's cross-section, what the lookup shows),
    // so the range in a volume's intensities grows with its cells' area. A coarse cascade, whose
    // cells are 4x and 16x the finest's area, then clips no sooner than the finest, and the finest
    // keeps its steps small.
    float encodeRange(const VolumeGrid& grid) const {
        return settings_.rgba8Range * grid.cellSize * grid.cellSize;
    }
    // The range of the volume last injected (inject()), in which propagate() and the bounces encode.
    float injectedEncodeRange() const { return injectedRange_; }
    // The cascade last injected (inject()'s `cascade`).
    uint32_t injectedCascade() const { return injectedCascade_; }
    // rgba8: where encodes note light over the range; null for the float formats, which do not clip.
    Rgba8Clipping* clipping() { return clipping_.get(); }
    const Rgba8Clipping* clipping() const { return clipping_.get(); }
    uint32_t gridSize() const { return settings_.gridSize; }

private:
    rhi::Device& device_;
    LpvSettings settings_;
    uint32_t columnLength_;
    bool layered_; // injection in one layered draw (rhi Caps::vertexShaderLayer)
    // Propagation reads the injection volume through texelFetch: the device has too few storage
    // image bindings for it (rhi Caps::storageImageBindings).
    bool injectedAsTexture_;
    float injectedRange_ = 0.0f; // encodeRange of the grid last injected
    uint32_t injectedCascade_ = 0;
    std::unique_ptr<Rgba8Clipping> clipping_; // rgba8 only
    std::array<rhi::TextureHandle, 3> inject_, accum_;
    // Partial sums between iterations, ping and pong, packed (packedTexelCount texels per cell),
    // partialSumSize^3.
    std::array<std::array<rhi::TextureHandle, 3>, 2> partial_{};
    rhi::GraphicsPipelineHandle injectPipeline_;
    bool shell_; // partialSumShell
    // By kernel role (LpvVolumes.cpp's Role); those of the other layout stay null.
    std::array<rhi::ComputePipelineHandle, 14> propagatePipelines_{};
    rhi::SamplerHandle linearSampler_; // the coarse cascade's result (handoff)
    rhi::SamplerHandle pointSampler_;  // the injection volume, read texel by texel
};

} // namespace lpv::gi
