// Injection and propagation passes.
#include "gi/LpvVolumes.h"

#include "GiShaders.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace lpv::gi {
namespace {

struct InjectUniforms {
    glm::vec4 gridOrigin;
    glm::vec4 lightDirection;
    glm::vec4 intensity;
    glm::ivec4 grid;
};

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

} // namespace

uint32_t packedTexelCount(ShFormat f) {
    switch (f) {
    case ShFormat::Rgba8:
        return 1;
    case ShFormat::Rgba32f:
    case ShFormat::Rgba16f:
        break;
    }
    return 3;
}

bool partialSumShell(const LpvSettings& s) {
    return s.cascades > 1;
}

uint32_t partialSumSize(const LpvSettings& s) {
    const uint32_t n = s.gridSize;
    return partialSumShell(s) ? n + 2 + (n & 1) : n;
}

uint32_t propagationColumnLength(uint32_t n, uint32_t concurrentWorkgroups) {
    if (concurrentWorkgroups == 0) return 1;
    const uint32_t columnGroups = ((n + 15) / 16) * ((n + 15) / 16);
    const uint32_t slabs = std::max(1u, (2 * concurrentWorkgroups + columnGroups - 1) / columnGroups);
    return std::max(1u, (n + slabs - 1) / slabs);
}

// Every texel of a format has the same format (the parameter keeps the per-texel question open).
rhi::Format packedTexelFormat(ShFormat f, uint32_t /*texel*/) {
    return f == ShFormat::Rgba16f ? rhi::Format::RGBA16F : rhi::Format::RGBA32UI;
}

LpvVolumes::LpvVolumes(rhi::Device& device, const LpvSettings& settings, uint32_t columnLength)
    : device_(device), settings_(settings),
      columnLength_(columnLength
                        ? columnLength
                        : propagationColumnLength(settings.gridSize, device.caps().concurrentWorkgroups)),
      layered_(device.caps().vertexShaderLayer),
      injectedAsTexture_(device.caps().storageImageBindings < kInjectedBindings),
      shell_(partialSumShell(settings)) {
    using namespace rhi;
    const uint32_t n = settings.gridSize;
    const Format injectFormat = settings.shFormat == ShFormat::Rgba32f ? Format::RGBA32F : Format::RGBA16F;
    const Format shFormat = shTextureFormat(settings.shFormat);
    const char* channels[3] = {"red", "green", "blue"};
    for (int c = 0; c < 3; ++c) {
        const auto volume = [&](Format f, uint32_t usage, const char* what) {
            return device.createTexture({TextureKind::Tex3D, f, n, n, n, 1, usage | kTextureTransfer,
                                         std::string("lpv ") + what + " " + channels[c], "gi.lpv"});
        };
        // Storage too: the propagation kernel reads it with imageLoad, or texelFetch where the
        // device has too few storage image bindings (propagate_body.glsl), and
        // further bounces write their reflected light here (MultipleBounces).
        inject_[size_t(c)] =
            volume(injectFormat, kTextureColorTarget | kTextureSampled | kTextureStorage, "injection");
        accum_[size_t(c)] = volume(shFormat, kTextureStorage | kTextureSampled, "accumulated");
    }
    const uint32_t padded = partialSumSize(settings);
    for (uint32_t t = 0; t < packedTexelCount(settings.shFormat); ++t)
        for (uint32_t p = 0; p < 2; ++p)
            partial_[p][t] = device.createTexture(
                {TextureKind::Tex3D, packedTexelFormat(settings.shFormat, t), padded, padded, padded, 1,
                 kTextureStorage | kTextureSampled | kTextureTransfer,
                 std::string(p ? "lpv partial sum pong " : "lpv partial sum ping ") + std::to_string(t),
                 "gi.lpv"});
    GraphicsPipelineDesc d;
    d.vertex = layered_ ? &shaders::inject_layered_vert : &shaders::inject_slice_vert;
    d.fragment = &shaders::inject_frag;
    d.topology = PrimitiveTopology::PointList;
    d.colorFormats = {injectFormat, injectFormat, injectFormat};
    d.blend = {BlendState::additive()};
    d.debugName = "lpv inject";
    injectPipeline_ = device.createPipeline(d);
    for (int role = 0; role < kRoles; ++role)
        if (shellRole(role) == shell_)
            propagatePipelines_[size_t(role)] = device.createPipeline(ComputePipelineDesc{
                &propagateShader(settings.shFormat, role, injectedAsTexture_), kRoleNames[role]});
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linearSampler_ = device.createSampler(linear);
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    if (encoded()) clipping_ = std::make_unique<Rgba8Clipping>(device);
}

LpvVolumes::~LpvVolumes() {
    device_.waitIdle();
    for (const auto* set : {&inject_, &accum_, &partial_[0], &partial_[1]})
        for (rhi::TextureHandle t : *set)
            if (t) device_.destroy(t);
    device_.destroy(injectPipeline_);
    for (rhi::ComputePipelineHandle p : propagatePipelines_)
        if (p) device_.destroy(p);
    device_.destroy(linearSampler_);
    device_.destroy(pointSampler_);
}

bool LpvVolumes::matches(const LpvSettings& s) const {
    return s.gridSize == settings_.gridSize && s.shFormat == settings_.shFormat &&
           s.rgba8Range == settings_.rgba8Range && partialSumShell(s) == shell_;
}

void LpvVolumes::inject(rhi::CommandList& cmd, rhi::BufferHandle vpls, uint32_t vplCount,
                        const VolumeGrid& grid, glm::vec3 lightDirection, float intensity) {
    const VplSource source{vpls, vplCount, glm::vec4(lightDirection, 0.0f)};
    inject(cmd, std::span(&source, 1), grid, intensity);
}

void LpvVolumes::inject(rhi::CommandList& cmd, std::span<const VplSource> sources, const VolumeGrid& grid,
                        float intensity, uint32_t cascade) {
    using namespace rhi;
    for (TextureHandle t : inject_)
        cmd.clearTexture(t, {0, 0, 0, 0});
    injectedRange_ = encodeRange(grid);
    injectedCascade_ = cascade;
    InjectUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    u.intensity = glm::vec4(intensity, 0, 0, 0);
    // One layered draw per source where the device lets the vertex shader pick the slice; else
    // every source once per slice (gridSize times the vertex work).
    const uint32_t passes = layered_ ? 1 : settings_.gridSize;
    for (uint32_t slice = 0; slice < passes; ++slice) {
        RenderPassDesc pass;
        for (uint32_t c = 0; c < 3; ++c) {
            pass.colors[c] = {inject_[c], 0, slice, LoadOp::Load};
            pass.colors[c].layered = layered_;
        }
        pass.colorCount = 3;
        pass.debugName = layered_ ? "lpv inject" : "lpv inject slice";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(injectPipeline_);
        for (const VplSource& source : sources) {
            if (source.count == 0) continue;
            u.lightDirection = source.light;
            u.grid = glm::ivec4(int(settings_.gridSize), int(slice), int(source.count), 0);
            cmd.pushUniforms(0, &u, sizeof(u));
            cmd.bindStorageBuffer(1, source.vpls);
            cmd.draw(source.count);
        }
        cmd.endRenderPass();
    }
}

std::array<rhi::TextureHandle, 3> LpvVolumes::createResult(const std::string& name) const {
    using namespace rhi;
    const uint32_t n = settings_.gridSize;
    const char* channels[3] = {"red", "green", "blue"};
    std::array<TextureHandle, 3> out{};
    for (int c = 0; c < 3; ++c)
        out[size_t(c)] = device_.createTexture({TextureKind::Tex3D, shTextureFormat(settings_.shFormat), n, n,
                                                n, 1, kTextureStorage | kTextureSampled | kTextureTransfer,
                                                name + " " + channels[c], "gi.lpv"});
    return out;
}

void LpvVolumes::propagate(rhi::CommandList& cmd, uint32_t iterations, rhi::TextureHandle faceTransmittance,
                           const std::array<rhi::TextureHandle, 3>* result, const CascadeHandoff* handoff) {
    // Bounded partial sums have nowhere to keep the coarser cascade's light (partialSumShell).
    if (handoff && !shell_)
        throw std::logic_error(
            "LpvVolumes::propagate: a cascade handoff needs volumes made for several cascades");
    // rgba8 propagates in the range of the grid last injected (encodeRange): there is none before.
    if (encoded() && injectedRange_ <= 0.0f)
        throw std::logic_error("LpvVolumes::propagate: rgba8 volumes propagate after an inject()");
    const std::array<rhi::TextureHandle, 3>& target = result ? *result : accum_;
    const uint32_t n = settings_.gridSize;
    const uint32_t column = columnLength_;
    const uint32_t texels = packedTexelCount(settings_.shFormat);
    PropagateUniforms u;
    u.grid = glm::ivec4(int(n), int(column), 0, 0);
    u.encode = glm::vec4(injectedRange_, 0, encoded() ? 1 : 0, 0);
    if (handoff) {
        const float coarseExtent = handoff->coarseGrid.cellSize * float(handoff->coarseGrid.size);
        const glm::vec3 firstCentre = handoff->fineGrid.origin + 0.5f * handoff->fineGrid.cellSize;
        u.handoff = glm::vec4((firstCentre - handoff->coarseGrid.origin) / coarseExtent,
                              handoff->fineGrid.cellSize / coarseExtent);
        const float ratio = handoff->fineGrid.cellSize / handoff->coarseGrid.cellSize;
        u.encode.y = ratio * ratio;
    }
    const int occluded = faceTransmittance ? 1 : 0;
    const auto bindInjected = [&] {
        for (uint32_t c = 0; c < 3; ++c)
            if (injectedAsTexture_)
                cmd.bindTexture(8 + c, inject_[c], pointSampler_);
            else
                cmd.bindStorageImage(8 + c, inject_[c]);
    };
    const auto bindIteration = [&](int role, uint32_t i, bool fromInjection, bool last) {
        cmd.bindPipeline(propagatePipelines_[size_t(role)]);
        cmd.pushUniforms(0, &u, sizeof(u));
        if (faceTransmittance) cmd.bindStorageImage(7, faceTransmittance);
        bindInjected();
        for (uint32_t c = 0; c < 3; ++c)
            if (last) cmd.bindStorageImage(4 + c, target[c]);
        for (uint32_t t = 0; t < texels; ++t) {
            if (!fromInjection) cmd.bindStorageImage(1 + t, partial_[(i + 1) % 2][t]);
            if (!last) cmd.bindStorageImage(4 + t, partial_[i % 2][t]);
        }
        if (last && clipping_) clipping_->bind(cmd, injectedCascade_);
        cmd.dispatch((n + 15) / 16, (n + 15) / 16, (n + column - 1) / column);
    };
    if (!shell_) {
        // y(0) is the injection volume; y(k+1) = x + P y(k) goes to partial_[k % 2]; the last
        // iteration writes y(N), the accumulated result, into target.
        for (uint32_t i = 0; i < iterations; ++i) {
            const bool first = i == 0, last = i + 1 == iterations;
            const int role = (first && last ? kOnly : first ? kFirst : last ? kLast : kNext) + 4 * occluded;
            bindIteration(role, i, first, last);
        }
        return;
    }
    // y(0) = x and the shell go to partial_[1] (the shell to partial_[0] too); y(k+1) = x + P y(k)
    // goes to partial_[k % 2]; the last iteration writes y(N), the accumulated result, into target.
    const uint32_t padded = partialSumSize(settings_);
    cmd.bindPipeline(propagatePipelines_[size_t(handoff ? kSeedHandoff : kSeed)]);
    cmd.pushUniforms(0, &u, sizeof(u));
    if (handoff)
        for (uint32_t c = 0; c < 3; ++c)
            cmd.bindTexture(20 + c, handoff->coarse[c], linearSampler_);
    bindInjected();
    for (uint32_t t = 0; t < texels; ++t) {
        cmd.bindStorageImage(1 + t, partial_[0][t]);
        cmd.bindStorageImage(4 + t, partial_[1][t]);
    }
    cmd.dispatch((padded + 7) / 8, (padded + 7) / 8, padded);
    for (uint32_t i = 0; i < iterations; ++i) {
        const bool last = i + 1 == iterations;
        bindIteration((last ? kShellLast : kShellNext) + 2 * occluded, i, false, last);
    }
}

} // namespace lpv::gi
