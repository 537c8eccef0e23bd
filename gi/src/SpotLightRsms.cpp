// Spot lights with their own RSM: the choice of lights, their RSMs and VPL clustering.
#include "gi/SpotLightRsms.h"

#include "GiShaders.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <string>

namespace lpv::gi {
namespace {

// std140 block `Params` of vpl_cluster.comp.
struct ClusterUniforms {
    glm::mat4 invLightViewProjection;
    glm::ivec4 sizes;
};

float importance(const engine::Light& l, const VolumeGrid& grid) {
    const float half = 0.5f * grid.cellSize * float(grid.size);
    const glm::vec3 toCentre = grid.origin + glm::vec3(half) - l.position;
    const float luminance = glm::dot(l.color, glm::vec3(0.2126f, 0.7152f, 0.0722f)) * l.intensity;
    return luminance / std::max(glm::dot(toCentre, toCentre), half * half);
}

// Distance from `p` to the farthest corner of the volume: as far as the volume needs a light's RSM.
float farthestCorner(glm::vec3 p, const VolumeGrid& grid) {
    const glm::vec3 lo = grid.origin, hi = grid.origin + grid.cellSize * float(grid.size);
    return glm::length(glm::max(glm::abs(p - lo), glm::abs(p - hi)));
}

} // namespace

uint32_t spotLightVplSide(const LpvSettings& settings) {
    const uint32_t side = settings.vplGridSide();
    return side % 2 == 0 ? side / 2 : side; // rsm % side == 0, so rsm % (side / 2) == 0
}

uint32_t spotLightCount(std::span<const engine::Light> lights) {
    return uint32_t(std::count_if(lights.begin(), lights.end(),
                                  [](const engine::Light& l) { return l.type == engine::LightType::Spot; }));
}

uint32_t selectRsmSpotLights(std::span<const engine::Light> lights, const VolumeGrid& grid,
                             std::span<uint32_t> out) {
    uint32_t count = 0;
    std::array<float, SpotLightRsms::kMaxLights> scores{};
    const uint32_t capacity = uint32_t(std::min(out.size(), scores.size()));
    for (uint32_t i = 0; i < uint32_t(lights.size()); ++i) {
        const engine::Light& l = lights[i];
        if (l.type != engine::LightType::Spot || !reachesVolume(analyticLight(l, 1.0f), grid)) continue;
        const float score = importance(l, grid);
        // Insertion into the sorted top list; an equal score stays behind the earlier light.
        uint32_t at = count;
        while (at > 0 && scores[at - 1] < score)
            --at;
        if (at >= capacity) continue;
        for (uint32_t k = std::min(count, capacity - 1); k > at; --k) {
            scores[k] = scores[k - 1];
            out[k] = out[k - 1];
        }
        scores[at] = score;
        out[at] = i;
        count = std::min(count + 1, capacity);
    }
    return count;
}

SpotLightRsms::SpotLightRsms(rhi::Device& device, const LpvSettings& settings)
    : device_(device), settings_(settings), capacity_(std::min(settings.lightRsms, kMaxLights)) {
    using namespace rhi;
    for (uint32_t k = 0; k < capacity_; ++k) {
        rsms_[k] = std::make_unique<ReflectiveShadowMap>(device, settings.rsmSize, RsmLight::Spot);
        vpls_[k] =
            device.createBuffer({uint64_t(spotLightVplCount(settings)) * 48, kBufferStorage | kBufferTransfer,
                                 MemoryAccess::GpuOnly, "spot light vpls " + std::to_string(k), "gi.vpl"});
    }
    if (capacity_ > 0)
        clusterPipeline_ =
            device.createPipeline(ComputePipelineDesc{&shaders::vpl_cluster_comp, "spot light vpl cluster"});
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

SpotLightRsms::~SpotLightRsms() {
    device_.waitIdle();
    for (uint32_t k = 0; k < capacity_; ++k)
        device_.destroy(vpls_[k]);
    if (clusterPipeline_) device_.destroy(clusterPipeline_);
    device_.destroy(pointSampler_);
}

void SpotLightRsms::select(std::span<const engine::Light> lights, const VolumeGrid& reach) {
    count_ = selectRsmSpotLights(lights, reach, std::span(selection_.data(), capacity_));
    reachGrid_ = reach;
    for (uint32_t k = 0; k < count_; ++k) {
        const engine::Light& spot = lights[selection_[k]];
        sources_[k] = {vpls_[k], spotLightVplCount(settings_), glm::vec4(spot.position, 1.0f)};
        reach_[k] = analyticLight(spot, 1.0f);
    }
}

uint32_t SpotLightRsms::sourcesReaching(const VolumeGrid& grid, std::span<VplSource> out) const {
    uint32_t n = 0;
    for (uint32_t k = 0; k < count_ && n < out.size(); ++k)
        if (reachesVolume(reach_[k], grid)) out[n++] = sources_[k];
    return n;
}

bool SpotLightRsms::selected(uint32_t index) const {
    for (uint32_t k = 0; k < count_; ++k)
        if (selection_[k] == index) return true;
    return false;
}

uint64_t SpotLightRsms::render(rhi::CommandList& cmd, const engine::GpuScene& scene,
                               std::span<const engine::Light> lights) {
    uint64_t triangles = 0;
    const uint32_t side = spotLightVplSide(settings_);
    for (uint32_t k = 0; k < count_; ++k) {
        const engine::Light& spot = lights[selection_[k]];
        ReflectiveShadowMap& rsm = *rsms_[k];
        triangles += rsm.renderSpot(cmd, scene, spot, farthestCorner(spot.position, reachGrid_));
        // The sun's clustering (vpl_cluster.comp): its unprojection holds for a perspective map.
        ClusterUniforms u;
        u.invLightViewProjection = glm::inverse(rsm.lightViewProjection());
        u.sizes = glm::ivec4(int(rsm.size()), int(side), int(rsm.size() / side), 0);
        cmd.bindPipeline(clusterPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindTexture(1, rsm.depth(), pointSampler_);
        cmd.bindTexture(2, rsm.normal(), pointSampler_);
        cmd.bindTexture(3, rsm.flux(), pointSampler_);
        cmd.bindStorageBuffer(4, vpls_[k]);
        cmd.dispatch((side + 7) / 8, (side + 7) / 8, 1);
    }
    return triangles;
}

} // namespace lpv::gi
