// Propagation (Kaplanyan & Dachsbacher 2010): N iterations of the 6-neighbour, 5-face scheme,
// each adding the injected light to the previous iteration's propagated light (y(k+1) = x + P y(k)),
// so the last writes the accumulated result. The partial sums ping-pong between the volumes'
// packed textures; with several cascades they carry a one-cell shell of what lies beyond the
// border (the coarser cascade's light). The kernel is gi/shaders/propagate_body.glsl.
#pragma once

#include "gi/LpvReference.h"
#include "gi/LpvSettings.h"
#include "gi/LpvVolumes.h"
#include "rhi/Device.h"

#include <array>
#include <cstdint>
#include <span>

namespace lpv::gi {

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

// One volume's propagation, as record()'s arguments.
struct PropagationJob {
    LpvVolumes* volumes = nullptr;
    rhi::TextureHandle faceTransmittance;
    const std::array<rhi::TextureHandle, 3>* result = nullptr;
    const CascadeHandoff* handoff = nullptr;
};

class LpvPropagation {
public:
    static constexpr size_t kMaxJobs = 4;

    // Whether `volumes` (2 or more) volumes made with `settings` propagate as slabs of one stacked
    // set of partial sums, each step of up to kMaxJobs of them one dispatch: float volumes with a
    // shell, on a device whose branches uniform over a workgroup cost one side only (a CPU
    // rasterizer runs every side: there each volume keeps its own dispatch and partial sums) and
    // with the bindings the kernel takes (16 storage images, 32 textures in a compute shader).
    static bool stacks(const rhi::Caps& caps, const LpvSettings& settings, uint32_t volumes);

    // For volumes made with `settings` (their size, format and partial-sum layout).
    // `columnLength`: cells each thread walks along z; 0 picks it from the device
    // (propagationColumnLength). Tests pin it to cover the shapes other devices get.
    // `volumes`: how many recordTogether() takes at once; where they stack (stacks()), the
    // propagation keeps their partial sums, and the volumes are made without (LpvVolumes).
    LpvPropagation(rhi::Device& device, const LpvSettings& settings, uint32_t columnLength = 0,
                   uint32_t volumes = 1);
    ~LpvPropagation();
    LpvPropagation(const LpvPropagation&) = delete;
    LpvPropagation& operator=(const LpvPropagation&) = delete;

    // Propagates `iterations` (>= 1) times from the injection volume of `volumes`, in the units of
    // the grid last injected (rgba8: LpvVolumes::injectedEncodeRange(); std::logic_error before any
    // injection); the result then holds the injected volume plus every iteration's propagated
    // light. With `faceTransmittance` (GeometryVolume), the flux through every face is attenuated
    // by it. `result`: where the last iteration writes (a set from LpvVolumes::createResult(), e.g.
    // another cascade's); volumes.accumulated() when null. `handoff`: outside the volume,
    // neighbours read the coarser cascade's result (in this volume's units) instead of nothing;
    // only for volumes with a shell (partialSumShell), std::logic_error otherwise.
    void record(rhi::CommandList& cmd, LpvVolumes& volumes, uint32_t iterations,
                rhi::TextureHandle faceTransmittance = {},
                const std::array<rhi::TextureHandle, 3>* result = nullptr,
                const CascadeHandoff* handoff = nullptr);
    // Several volumes (up to kMaxJobs, each made with these settings, none another's handoff
    // source) propagated step by step together: each step of all of them is one stage of the
    // dependent chain, not one per volume; stacked (stacked()), one dispatch. Stacked, every job
    // or none has faces, and only the first three a handoff (std::logic_error otherwise).
    void recordTogether(rhi::CommandList& cmd, std::span<const PropagationJob> jobs, uint32_t iterations);

    // The volumes' partial sums are this propagation's, stacked (stacks()).
    bool stacked() const { return slabs_ > 0; }

private:
    void recordStacked(rhi::CommandList& cmd, std::span<const PropagationJob> jobs, uint32_t iterations);
    // The partial sums job j ping-pongs between: its volumes', or the stack's (whose first slab
    // the one-volume kernels address like a volume's own).
    const std::array<std::array<rhi::TextureHandle, 3>, 2>& partialSumsOf(const PropagationJob& job) const;

    rhi::Device& device_;
    LpvSettings settings_;
    uint32_t columnLength_;
    // The kernels read the injection volume through texelFetch: the device has too few storage
    // image bindings for it (rhi Caps::storageImageBindings).
    bool injectedAsTexture_;
    bool shell_; // partialSumShell
    // By kernel role (LpvPropagation.cpp's Role); those of the other layout stay null.
    std::array<rhi::ComputePipelineHandle, 14> pipelines_{};
    rhi::SamplerHandle linearSampler_; // the coarse cascade's result (handoff)
    rhi::SamplerHandle pointSampler_;  // the injection volume, read texel by texel
    // Stacked: the slabs of the partial sums (0: not stacked), their textures (ping and pong,
    // packedTexelCount each) and the slab kernels (StackedRole in LpvPropagation.cpp).
    uint32_t slabs_ = 0;
    std::array<std::array<rhi::TextureHandle, 3>, 2> stack_{};
    std::array<rhi::ComputePipelineHandle, 5> stackedPipelines_{};
};

} // namespace lpv::gi
