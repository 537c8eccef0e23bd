// Spot and point lights with their own RSM: the choice of lights, their RSMs and VPL clustering.
#include "gi/SpotLightRsms.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <string>

namespace lpv::gi {
namespace {

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

uint32_t lightCount(std::span<const engine::Light> lights, engine::LightType type) {
    return uint32_t(
        std::count_if(lights.begin(), lights.end(), [&](const engine::Light& l) { return l.type == type; }));
}

uint32_t selectRsmLights(std::span<const engine::Light> lights, engine::LightType type,
                         const VolumeGrid& grid, std::span<uint32_t> out) {
    uint32_t count = 0;
    if (out.empty()) return 0; // none wanted (gi.point_light_rsms=0): skip the scoring
    std::array<float, SpotLightRsms::kMaxLights> scores{}; // at most 4 of either kind
    const uint32_t capacity = uint32_t(std::min(out.size(), scores.size()));
    for (uint32_t i = 0; i < uint32_t(lights.size()); ++i) {
        const engine::Light& l = lights[i];
        if (l.type != type || !reachesVolume(analyticLight(l, 1.0f), grid)) continue;
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
    : device_(device), settings_(settings), capacity_(std::min(settings.lightRsms, kMaxLights)),
      pointCapacity_(std::min(settings.pointLightRsms, kMaxPointLights)) {
    using namespace rhi;
    for (uint32_t k = 0; k < capacity_ + kCubeFaces * pointCapacity_; ++k) {
        rsms_[k] = std::make_unique<ReflectiveShadowMap>(device, settings.rsmSize, RsmLight::Spot);
        vpls_[k] =
            device.createBuffer({uint64_t(spotLightVplSlots(settings)) * 48, kBufferStorage | kBufferTransfer,
                                 MemoryAccess::GpuOnly, "light rsm vpls " + std::to_string(k), "gi.vpl"});
    }
    if (capacity_ + pointCapacity_ > 0) clustering_.emplace(device, "spot light vpl cluster");
}

SpotLightRsms::~SpotLightRsms() {
    device_.waitIdle();
    for (rhi::BufferHandle b : vpls_)
        if (b) device_.destroy(b);
}

void SpotLightRsms::select(std::span<const engine::Light> lights, const VolumeGrid& reach) {
    count_ = selectRsmLights(lights, engine::LightType::Spot, reach, std::span(selection_.data(), capacity_));
    pointCount_ = selectRsmLights(lights, engine::LightType::Point, reach,
                                  std::span(selection_.data() + count_, pointCapacity_));
    reachGrid_ = reach;
    // RSM slots: one per spot, then six per point light, each face its own VPL source (the VPLs'
    // half-cell shift runs along their own line from the light either way).
    rsmCount_ = 0;
    for (uint32_t k = 0; k < count_ + pointCount_; ++k) {
        const engine::Light& light = lights[selection_[k]];
        const float far = farthestCorner(light.position, reach);
        for (uint32_t f = 0; f < (k < count_ ? 1u : kCubeFaces); ++f, ++rsmCount_) {
            reach_[rsmCount_] = analyticLight(light, 1.0f);
            // As record() fits it.
            const SpotRsmFit fit = k < count_ ? fitSpotRsm(light, far) : fitCubeFace(light, f, far);
            frusta_[rsmCount_] = fit.viewProjection;
            sources_[rsmCount_] = {vpls_[rsmCount_], spotLightVplSlots(settings_),
                                   glm::vec4(light.position, 1.0f), fit.viewProjection};
            // A VPL's block of texels: (size / side)^2 texels of (2 tan / size)^2 sr each on the axis.
            const float block = 2.0f * fit.tanHalfAngle / float(spotLightVplSide(settings_));
            surfels_[rsmCount_] = {vpls_[rsmCount_], spotLightVplSlots(settings_),
                                   light.position,   fit.axis,
                                   block * block,    reach_[rsmCount_]};
        }
    }
}

namespace {
engine::Bounds boxOf(const VolumeGrid& grid) {
    engine::Bounds box;
    box.add(grid.origin);
    box.add(grid.origin + glm::vec3(grid.cellSize * float(grid.size)));
    return box;
}
} // namespace

bool SpotLightRsms::reaches(uint32_t slot, const VolumeGrid& grid, const engine::Bounds& box) const {
    return reachesVolume(reach_[slot], grid) && !box.outsideClipVolume(frusta_[slot]);
}

uint32_t SpotLightRsms::sourcesReaching(const VolumeGrid& grid, std::span<VplSource> out) const {
    return copyReaching(grid, std::span<const VplSource>(sources_.data(), rsmCount_), out);
}

uint32_t SpotLightRsms::surfelsReaching(const VolumeGrid& grid, std::span<PointLightSurfels> out) const {
    return copyReaching(grid, std::span<const PointLightSurfels>(surfels_.data(), rsmCount_), out);
}

template <typename T>
uint32_t SpotLightRsms::copyReaching(const VolumeGrid& grid, std::span<const T> all, std::span<T> out) const {
    const engine::Bounds box = boxOf(grid);
    uint32_t n = 0;
    for (uint32_t k = 0; k < all.size() && n < out.size(); ++k)
        if (reaches(k, grid, box)) out[n++] = all[k];
    return n;
}

bool SpotLightRsms::selected(uint32_t index) const {
    for (uint32_t k = 0; k < count_ + pointCount_; ++k)
        if (selection_[k] == index) return true;
    return false;
}

uint64_t SpotLightRsms::record(rhi::CommandList& cmd, const engine::GpuScene& scene,
                               rhi::TextureHandle specularAlbedo, std::span<const engine::Light> lights) {
    uint64_t triangles = 0;
    uint32_t slot = 0;
    for (uint32_t k = 0; k < count_ + pointCount_; ++k) {
        const engine::Light& light = lights[selection_[k]];
        const float reach = farthestCorner(light.position, reachGrid_);
        for (uint32_t f = 0; f < (k < count_ ? 1u : kCubeFaces); ++f, ++slot) {
            ReflectiveShadowMap& rsm = *rsms_[slot];
            triangles +=
                k < count_
                    ? rsm.recordSpot(cmd, scene, specularAlbedo, light, reach, settings_.rsmLodTexels)
                    : rsm.recordCubeFace(cmd, scene, specularAlbedo, light, f, reach, settings_.rsmLodTexels);
            clustering_->record(cmd, rsm, spotLightVplSide(settings_), vpls_[slot]);
        }
    }
    return triangles;
}

} // namespace lpv::gi
