// Analytic point and spot lights: packing, volume culling and the CPU reference of the formula.
#include "gi/AnalyticLight.h"

#include "gi/ShBasis.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lpv::gi {
namespace {

// Cosines of a point light's "cone": smoothstep(-3, -2, dot) is 1 for every direction.
constexpr float kPointCosOuter = -3.0f;
constexpr float kPointCosInner = -2.0f;

float smoothstep(float edge0, float edge1, float x) {
    const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

} // namespace

AnalyticLight analyticLight(const engine::Light& l, float intensityScale) {
    AnalyticLight a;
    a.positionInvRange2 = glm::vec4(l.position, l.range > 0.0f ? 1.0f / (l.range * l.range) : 0.0f);
    const glm::vec3 intensity = l.color * (l.intensity * intensityScale);
    const bool spot = l.type == engine::LightType::Spot;
    const float cosOuter = std::cos(l.outerConeAngle);
    // smoothstep needs edge0 < edge1; a hard-edged cone (inner == outer) gets a sliver of falloff.
    const float cosInner = std::max(std::cos(l.innerConeAngle), cosOuter + 1e-4f);
    const float dirLength = glm::length(l.direction);
    const glm::vec3 dir = dirLength > 0.0f ? l.direction / dirLength : glm::vec3(0.0f, -1.0f, 0.0f);
    a.intensityCos = glm::vec4(intensity, spot ? cosOuter : kPointCosOuter);
    a.spotCos = glm::vec4(dir, spot ? cosInner : kPointCosInner);
    return a;
}

bool reachesVolume(const AnalyticLight& light, const VolumeGrid& grid) {
    const glm::vec3 rgb(light.intensityCos);
    if (!(std::max({rgb.r, rgb.g, rgb.b}) > 0.0f)) return false;
    // Distance from the light to the volume's box against the range.
    const glm::vec3 lo = grid.origin, hi = grid.origin + grid.cellSize * float(grid.size);
    const glm::vec3 p(light.positionInvRange2);
    const glm::vec3 outside = p - glm::clamp(p, lo, hi);
    return glm::dot(outside, outside) * light.positionInvRange2.w < 1.0f;
}

ShCell analyticLightCell(const AnalyticLight& light, const VolumeGrid& grid, glm::ivec3 cell) {
    ShCell out;
    const float s = grid.cellSize;
    const glm::vec3 toCell = grid.origin + (glm::vec3(cell) + 0.5f) * s - glm::vec3(light.positionInvRange2);
    // The light's own cell: isotropic there, no direction of arrival.
    if (glm::all(glm::lessThan(glm::abs(toCell), glm::vec3(0.5f * s)))) return out;
    const float d2 = glm::dot(toCell, toCell);
    const float q = d2 * light.positionInvRange2.w; // (d / range)^2
    if (q >= 1.0f) return out;
    const glm::vec3 w = toCell / std::sqrt(d2);
    const float spot =
        smoothstep(light.intensityCos.w, light.spotCos.w, glm::dot(w, glm::vec3(light.spotCos)));
    // Flux through the cell's cross-section (s^2 / d^2 sr of the light, in the range window), as a
    // cosine lobe of intensity flux / pi along w.
    const float flux = spot * (1.0f - q * q) * s * s / d2;
    const glm::vec4 lobe = shCosineLobe(w) * (flux / kPi);
    out.r = lobe * light.intensityCos.r;
    out.g = lobe * light.intensityCos.g;
    out.b = lobe * light.intensityCos.b;
    return out;
}

void addAnalyticLightsReference(ShVolume& volume, const VolumeGrid& grid,
                                std::span<const AnalyticLight> lights) {
    const int n = int(volume.size());
    for (const AnalyticLight& light : lights)
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const ShCell c = analyticLightCell(light, grid, {x, y, z});
                    ShCell& dst = volume.at(uint32_t(x), uint32_t(y), uint32_t(z));
                    dst.r += c.r;
                    dst.g += c.g;
                    dst.b += c.b;
                }
}

} // namespace lpv::gi
