// The propagation pass: the kernel's roles and its iterations.
#include "gi/LpvPropagation.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace lpv::gi {
namespace {

// std140 block `Propagate` of propagate_body.glsl.
struct PropagateUniforms {
    glm::ivec4 grid;
    glm::vec4 encode;
    glm::vec4 handoff;
};

// Kernel roles (propagate_body.glsl, gi/CMakeLists.txt). Bounded partial sums: the first
// iteration reads the injection, the last writes the result, `only` does both; with or without
// occlusion. With a shell: the seed (with or without the coarser cascade around), then iterations
// and the last one, with or without occlusion.
enum Role {
    kFirst,
    kNext,
    kLast,
    kOnly,
    kFirstOccluded,
    kNextOccluded,
    kLastOccluded,
    kOnlyOccluded,
    kSeed,
    kSeedHandoff,
    kShellNext,
    kShellLast,
    kShellNextOccluded,
    kShellLastOccluded,
    kRoles
};
const char* const kRoleNames[kRoles] = {"lpv propagate first",
                                        "lpv propagate",
                                        "lpv propagate last",
                                        "lpv propagate once",
                                        "lpv propagate first (occluded)",
                                        "lpv propagate (occluded)",
                                        "lpv propagate last (occluded)",
                                        "lpv propagate once (occluded)",
                                        "lpv propagate seed",
                                        "lpv propagate seed (handoff)",
                                        "lpv propagate (shell)",
                                        "lpv propagate last (shell)",
                                        "lpv propagate (shell, occluded)",
                                        "lpv propagate last (shell, occluded)"};

bool shellRole(int role) {
    return role >= kSeed;
}

// The kernels' images take bindings up to kInjectedBindings (the injection volume's, 8-10);
// `fetch` variants read that volume through texelFetch and keep to the portable 8.
constexpr uint32_t kInjectedBindings = 11;

const rhi::ShaderBinary& propagateShader(ShFormat f, int role, bool fetch) {
    using namespace shaders;
#define LPV_ROLES(format, suffix)                                                                            \
    {                                                                                                        \
        &propagate_##format##_first##suffix##_comp, &propagate_##format##_next##suffix##_comp,               \
            &propagate_##format##_last##suffix##_comp, &propagate_##format##_only##suffix##_comp,            \
            &propagate_##format##_first_occluded##suffix##_comp,                                             \
            &propagate_##format##_next_occluded##suffix##_comp,                                              \
            &propagate_##format##_last_occluded##suffix##_comp,                                              \
            &propagate_##format##_only_occluded##suffix##_comp, &propagate_##format##_seed##suffix##_comp,   \
            &propagate_##format##_seed_handoff##suffix##_comp,                                               \
            &propagate_##format##_shell_next##suffix##_comp,                                                 \
            &propagate_##format##_shell_last##suffix##_comp,                                                 \
            &propagate_##format##_shell_next_occluded##suffix##_comp,                                        \
            &propagate_##format##_shell_last_occluded##suffix##_comp                                         \
    }
    static const rhi::ShaderBinary* const table[2][3][kRoles] = {
        {LPV_ROLES(rgba8, ), LPV_ROLES(rgba16f, ), LPV_ROLES(rgba32f, )},
        {LPV_ROLES(rgba8, _fetch), LPV_ROLES(rgba16f, _fetch), LPV_ROLES(rgba32f, _fetch)}};
#undef LPV_ROLES
    const int row = f == ShFormat::Rgba8 ? 0 : f == ShFormat::Rgba16f ? 1 : 2;
    return *table[fetch ? 1 : 0][row][role];
}

// The stacked kernels (`_slabs`, propagate_body.glsl's SLABS): one dispatch for every volume.
enum StackedRole { kStackedSeed, kStackedNext, kStackedLast, kStackedNextOccluded, kStackedLastOccluded };
// std140 block `Propagate` of propagate_body.glsl under SLABS.
struct StackedUniforms {
    glm::ivec4 grid;
    std::array<glm::vec4, LpvPropagation::kMaxJobs> encode;
    std::array<glm::vec4, LpvPropagation::kMaxJobs> handoff;
};
// Their bindings, three a slab where a set of SH textures (propagate_body.glsl): the coarser
// cascade's result around slabs 0-2 (seed), each slab's injection volume, result (last step) and
// faces.
constexpr uint32_t kSlabHandoff = 7, kSlabInjected = 16, kSlabResult = 4, kSlabFaces = 28;
constexpr uint32_t kSlabHandoffs = 3;

const rhi::ShaderBinary& stackedShader(ShFormat f, int role) {
    using namespace shaders;
    static const rhi::ShaderBinary* const table[2][5] = {
        {&propagate_rgba16f_seed_slabs_comp, &propagate_rgba16f_shell_next_slabs_comp,
         &propagate_rgba16f_shell_last_slabs_comp, &propagate_rgba16f_shell_next_occluded_slabs_comp,
         &propagate_rgba16f_shell_last_occluded_slabs_comp},
        {&propagate_rgba32f_seed_slabs_comp, &propagate_rgba32f_shell_next_slabs_comp,
         &propagate_rgba32f_shell_last_slabs_comp, &propagate_rgba32f_shell_next_occluded_slabs_comp,
         &propagate_rgba32f_shell_last_occluded_slabs_comp}};
    return *table[f == ShFormat::Rgba32f ? 1 : 0][role];
}

// The coarse volume's uvw at the fine volume's first cell centre and per cell, and the scale
// from the coarse cells' intensity to the fine ones' (their cross-sections' ratio).
glm::vec4 handoffPlacement(const CascadeHandoff& handoff) {
    const float coarseExtent = handoff.coarseGrid.cellSize * float(handoff.coarseGrid.size);
    const glm::vec3 firstCentre = handoff.fineGrid.origin + 0.5f * handoff.fineGrid.cellSize;
    return glm::vec4((firstCentre - handoff.coarseGrid.origin) / coarseExtent,
                     handoff.fineGrid.cellSize / coarseExtent);
}
float handoffScale(const CascadeHandoff& handoff) {
    const float ratio = handoff.fineGrid.cellSize / handoff.coarseGrid.cellSize;
    return ratio * ratio;
}

} // namespace

bool LpvPropagation::stacks(const rhi::Caps& caps, const LpvSettings& settings, uint32_t volumes) {
    return volumes > 1 && partialSumShell(settings) && settings.shFormat != ShFormat::Rgba8 &&
           !caps.maskedBranches && caps.storageImageBindings >= kSlabResult + 3 * kMaxJobs &&
           caps.computeTextureBindings >= kSlabFaces + kMaxJobs &&
           caps.max3DTextureSize >= partialSumSize(settings) * volumes;
}

uint32_t propagationColumnLength(uint32_t n, uint32_t concurrentWorkgroups) {
    if (concurrentWorkgroups == 0) return 1;
    const uint32_t columnGroups = ((n + 15) / 16) * ((n + 15) / 16);
    const uint32_t slabs = std::max(1u, (2 * concurrentWorkgroups + columnGroups - 1) / columnGroups);
    return std::max(1u, (n + slabs - 1) / slabs);
}

LpvPropagation::LpvPropagation(rhi::Device& device, const LpvSettings& settings, uint32_t columnLength,
                               uint32_t volumes)
    : device_(device), settings_(settings),
      columnLength_(columnLength
                        ? columnLength
                        : propagationColumnLength(settings.gridSize, device.caps().concurrentWorkgroups)),
      injectedAsTexture_(device.caps().storageImageBindings < kInjectedBindings),
      shell_(partialSumShell(settings)) {
    using namespace rhi;
    for (int role = 0; role < kRoles; ++role)
        if (shellRole(role) == shell_)
            pipelines_[size_t(role)] = device.createPipeline(ComputePipelineDesc{
                &propagateShader(settings.shFormat, role, injectedAsTexture_), kRoleNames[role]});
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linearSampler_ = device.createSampler(linear);
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    if (!stacks(device.caps(), settings, volumes)) return;
    slabs_ = volumes;
    const uint32_t padded = partialSumSize(settings);
    for (uint32_t t = 0; t < packedTexelCount(settings.shFormat); ++t)
        for (uint32_t p = 0; p < 2; ++p)
            stack_[p][t] = device.createTexture(
                {TextureKind::Tex3D, packedTexelFormat(settings.shFormat, t), padded, padded, padded * slabs_,
                 1, kTextureStorage | kTextureSampled | kTextureTransfer,
                 std::string(p ? "lpv partial sums pong, stacked " : "lpv partial sums ping, stacked ") +
                     std::to_string(t),
                 "gi.lpv"});
    static const char* const kStackedNames[5] = {
        "lpv propagate seed (stacked)", "lpv propagate (stacked)", "lpv propagate last (stacked)",
        "lpv propagate (stacked, occluded)", "lpv propagate last (stacked, occluded)"};
    for (int role = 0; role < 5; ++role)
        stackedPipelines_[size_t(role)] = device.createPipeline(
            ComputePipelineDesc{&stackedShader(settings.shFormat, role), kStackedNames[role]});
}

LpvPropagation::~LpvPropagation() {
    for (rhi::ComputePipelineHandle p : pipelines_)
        if (p) device_.destroy(p);
    for (rhi::ComputePipelineHandle p : stackedPipelines_)
        if (p) device_.destroy(p);
    for (const auto& set : stack_)
        for (rhi::TextureHandle t : set)
            if (t) device_.destroy(t);
    device_.destroy(linearSampler_);
    device_.destroy(pointSampler_);
}

void LpvPropagation::record(rhi::CommandList& cmd, LpvVolumes& volumes, uint32_t iterations,
                            rhi::TextureHandle faceTransmittance,
                            const std::array<rhi::TextureHandle, 3>* result, const CascadeHandoff* handoff) {
    const PropagationJob job{&volumes, faceTransmittance, result, handoff};
    recordTogether(cmd, std::span(&job, 1), iterations);
}

void LpvPropagation::recordTogether(rhi::CommandList& cmd, std::span<const PropagationJob> jobs,
                                    uint32_t iterations) {
    if (jobs.size() > kMaxJobs) throw std::logic_error("LpvPropagation::recordTogether: more than 4 volumes");
    if (stacked() && jobs.size() > slabs_)
        throw std::logic_error("LpvPropagation::recordTogether: more volumes than it was made for");
    if (stacked() && jobs.size() > 1) return recordStacked(cmd, jobs, iterations);
    const uint32_t n = settings_.gridSize;
    const uint32_t column = columnLength_;
    const uint32_t texels = packedTexelCount(settings_.shFormat);
    std::array<PropagateUniforms, kMaxJobs> uniforms;
    for (size_t j = 0; j < jobs.size(); ++j) {
        const PropagationJob& job = jobs[j];
        // Bounded partial sums have nowhere to keep the coarser cascade's light (partialSumShell).
        if (job.handoff && !shell_)
            throw std::logic_error(
                "LpvPropagation::record: a cascade handoff needs volumes made for several cascades");
        // rgba8 propagates in the range of the grid last injected (encodeRange): there is none before.
        const bool encoded = job.volumes->encoded();
        if (encoded && job.volumes->injectedEncodeRange() <= 0.0f)
            throw std::logic_error("LpvPropagation::record: rgba8 volumes propagate after an injection");
        PropagateUniforms& u = uniforms[j];
        u = {};
        u.grid = glm::ivec4(int(n), int(column), 0, 0);
        u.encode = glm::vec4(job.volumes->injectedEncodeRange(), 0, encoded ? 1 : 0, 0);
        if (const CascadeHandoff* handoff = job.handoff) {
            u.handoff = handoffPlacement(*handoff);
            u.encode.y = handoffScale(*handoff);
        }
    }
    const auto bindInjected = [&](const PropagationJob& job) {
        for (uint32_t c = 0; c < 3; ++c)
            if (injectedAsTexture_)
                cmd.bindTexture(8 + c, job.volumes->injected()[c], pointSampler_);
            else
                cmd.bindStorageImage(8 + c, job.volumes->injected()[c]);
    };
    const auto bindIteration = [&](size_t j, int role, uint32_t i, bool fromInjection, bool last) {
        const PropagationJob& job = jobs[j];
        const std::array<rhi::TextureHandle, 3>& target =
            job.result ? *job.result : job.volumes->accumulated();
        const auto& partial = partialSumsOf(job);
        cmd.bindPipeline(pipelines_[size_t(role)]);
        cmd.pushUniforms(0, &uniforms[j], sizeof(PropagateUniforms));
        if (job.faceTransmittance) cmd.bindStorageImage(7, job.faceTransmittance);
        bindInjected(job);
        for (uint32_t c = 0; c < 3; ++c)
            if (last) cmd.bindStorageImage(4 + c, target[c]);
        for (uint32_t t = 0; t < texels; ++t) {
            if (!fromInjection) cmd.bindStorageImage(1 + t, partial[(i + 1) % 2][t]);
            if (!last) cmd.bindStorageImage(4 + t, partial[i % 2][t]);
        }
        if (Rgba8Clipping* clipping = job.volumes->clipping(); last && clipping)
            clipping->bind(cmd, job.volumes->injectedCascade());
        cmd.dispatch((n + 15) / 16, (n + 15) / 16, (n + column - 1) / column);
    };
    // Step by step, every volume's step before the next step of any: the volumes do not depend on
    // each other, so each step is one stage of the GPU's dependent chain however many there are.
    if (!shell_) {
        // y(0) is the injection volume; y(k+1) = x + P y(k) goes to partial[k % 2]; the last
        // iteration writes y(N), the accumulated result, into the target.
        for (uint32_t i = 0; i < iterations; ++i)
            for (size_t j = 0; j < jobs.size(); ++j) {
                const bool first = i == 0, last = i + 1 == iterations;
                const int occluded = jobs[j].faceTransmittance ? 4 : 0;
                bindIteration(j,
                              (first && last ? kOnly
                               : first       ? kFirst
                               : last        ? kLast
                                             : kNext) +
                                  occluded,
                              i, first, last);
            }
        return;
    }
    // y(0) = x and the shell go to partial[1] (the shell to partial[0] too); y(k+1) = x + P y(k)
    // goes to partial[k % 2]; the last iteration writes y(N), the accumulated result, into the target.
    const uint32_t padded = partialSumSize(settings_);
    for (size_t j = 0; j < jobs.size(); ++j) {
        const PropagationJob& job = jobs[j];
        const auto& partial = partialSumsOf(job);
        cmd.bindPipeline(pipelines_[size_t(job.handoff ? kSeedHandoff : kSeed)]);
        cmd.pushUniforms(0, &uniforms[j], sizeof(PropagateUniforms));
        if (job.handoff)
            for (uint32_t c = 0; c < 3; ++c)
                cmd.bindTexture(20 + c, job.handoff->coarse[c], linearSampler_);
        bindInjected(job);
        for (uint32_t t = 0; t < texels; ++t) {
            cmd.bindStorageImage(1 + t, partial[0][t]);
            cmd.bindStorageImage(4 + t, partial[1][t]);
        }
        cmd.dispatch((padded + 7) / 8, (padded + 7) / 8, padded);
    }
    for (uint32_t i = 0; i < iterations; ++i)
        for (size_t j = 0; j < jobs.size(); ++j) {
            const bool last = i + 1 == iterations;
            bindIteration(j, (last ? kShellLast : kShellNext) + (jobs[j].faceTransmittance ? 2 : 0), i, false,
                          last);
        }
}

const std::array<std::array<rhi::TextureHandle, 3>, 2>&
LpvPropagation::partialSumsOf(const PropagationJob& job) const {
    return stacked() ? stack_ : job.volumes->partialSums();
}

void LpvPropagation::recordStacked(rhi::CommandList& cmd, std::span<const PropagationJob> jobs,
                                   uint32_t iterations) {
    const uint32_t n = settings_.gridSize;
    const uint32_t column = columnLength_;
    const uint32_t padded = partialSumSize(settings_);
    const uint32_t texels = packedTexelCount(settings_.shFormat);
    const uint32_t zGroups = (n + column - 1) / column;
    const uint32_t count = uint32_t(jobs.size());
    const bool occluded = bool(jobs[0].faceTransmittance);
    StackedUniforms u{};
    u.grid = glm::ivec4(int(n), int(column), int(zGroups), int(padded));
    for (uint32_t j = 0; j < count; ++j) {
        if (bool(jobs[j].faceTransmittance) != occluded)
            throw std::logic_error("LpvPropagation::recordTogether: stacked volumes all have faces or none");
        if (const CascadeHandoff* handoff = jobs[j].handoff) {
            if (j >= kSlabHandoffs)
                throw std::logic_error(
                    "LpvPropagation::recordTogether: a stacked handoff past the third volume");
            u.handoff[j] = handoffPlacement(*handoff);
            u.encode[j].y = handoffScale(*handoff);
        }
    }
    // A slab past the jobs binds the last job's textures: no workgroup of it runs.
    const auto job = [&](uint32_t s) -> const PropagationJob& { return jobs[std::min(s, count - 1)]; };
    const auto bindInjected = [&] {
        for (uint32_t s = 0; s < kMaxJobs; ++s)
            for (uint32_t c = 0; c < 3; ++c)
                cmd.bindTexture(kSlabInjected + 3 * s + c, job(s).volumes->injected()[c], pointSampler_);
    };
    // y(0) = x and the shell go to the pong slabs (the shell to the ping ones too), as record()'s.
    cmd.bindPipeline(stackedPipelines_[kStackedSeed]);
    cmd.pushUniforms(0, &u, sizeof(u));
    bindInjected();
    for (uint32_t s = 0; s < kSlabHandoffs; ++s)
        for (uint32_t c = 0; c < 3; ++c)
            if (const CascadeHandoff* handoff = job(s).handoff)
                cmd.bindTexture(kSlabHandoff + 3 * s + c, handoff->coarse[c], linearSampler_);
            else // read by no texel: the slab has no handoff (its uniform's w is 0)
                cmd.bindTexture(kSlabHandoff + 3 * s + c, job(s).volumes->injected()[c], pointSampler_);
    for (uint32_t t = 0; t < texels; ++t) {
        cmd.bindStorageImage(1 + t, stack_[0][t]);
        cmd.bindStorageImage(4 + t, stack_[1][t]);
    }
    cmd.dispatch((padded + 7) / 8, (padded + 7) / 8, padded * count);
    for (uint32_t i = 0; i < iterations; ++i) {
        const bool last = i + 1 == iterations;
        cmd.bindPipeline(
            stackedPipelines_[size_t((last ? kStackedLast : kStackedNext) + (occluded ? 2 : 0))]);
        cmd.pushUniforms(0, &u, sizeof(u));
        bindInjected();
        if (occluded)
            for (uint32_t s = 0; s < kMaxJobs; ++s)
                cmd.bindTexture(kSlabFaces + s, job(s).faceTransmittance, pointSampler_);
        for (uint32_t t = 0; t < texels; ++t) {
            cmd.bindStorageImage(1 + t, stack_[(i + 1) % 2][t]);
            if (!last) cmd.bindStorageImage(4 + t, stack_[i % 2][t]);
        }
        if (last)
            for (uint32_t s = 0; s < kMaxJobs; ++s) {
                const std::array<rhi::TextureHandle, 3>& target =
                    job(s).result ? *job(s).result : job(s).volumes->accumulated();
                for (uint32_t c = 0; c < 3; ++c)
                    cmd.bindStorageImage(kSlabResult + 3 * s + c, target[c]);
            }
        cmd.dispatch((n + 15) / 16, (n + 15) / 16, zGroups * count);
    }
}

} // namespace lpv::gi
