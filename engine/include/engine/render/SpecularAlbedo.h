// How much of the light a glossy surface gathers from around its mirror direction it reflects
// toward the viewer: the second factor of the split-sum approximation (Karis 2013, "Real Shading in
// Unreal Engine 4"). The GI's glossy march gathers radiance over a cone widened by roughness (the
// first factor); the lighting pass weighs it by F0 x scale + bias from this table instead of a plain
// Schlick Fresnel, which on rough surfaces at grazing angles reflected up to 4x too much.
#pragma once

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace lpv::engine {

// F0 x scale + bias is the directional albedo of the specular lobe seen at that angle.
//
// The two directions are the light directions the lobe gathers from, summed with the weights of
// scale and of bias, in the plane of the normal and the view: x along the normal, y along the
// mirror direction's part across it. (F0 x scaleDirection + biasDirection) / (F0 x scale + bias) is
// then the mean direction of the lobe's light, per channel of F0, its length shorter the wider the
// lobe: 1 for a mirror, about 0.63 at roughness 1 (the cosine lobe's is 2/3). For radiance linear in
// the direction, as an L1 spherical-harmonics field (the LPV) is, the lobe's mean radiance is that
// field evaluated at this vector, exactly: the GI's lookup reflects the volume this way where the
// glossy march does not run (gi/shaders/lpv_lookup.glsl).
struct SpecularAlbedo {
    float scale = 0.0f;
    float bias = 0.0f;
    glm::vec2 scaleDirection{0.0f};
    glm::vec2 biasDirection{0.0f};
};

// The integral over GGX-distributed microfacet normals (Hammersley points, `samples` of them) of
// the lobe seen at cos(view angle) `cosView` from a surface of perceptual `roughness` (GGX alpha =
// roughness^2, as glTF defines it), with Smith-Schlick masking (k = alpha / 2) and Schlick's
// Fresnel.
SpecularAlbedo integrateSpecularAlbedo(float cosView, float roughness, uint32_t samples);

// What glTF's fresnel_mix leaves a surface's diffuse base of a light arriving at cos(angle)
// `cosLight`, in all it sends out: the base shows 1 - F(v.h) of it toward each view v, and over the
// hemisphere of views, weighted by their cosine, that is (1 - F0) x (1 - this), the mean of Schlick's
// (1 - v.h)^5. It does not depend on roughness (the mix weighs by the half vector, not by the lobe):
// 8e-5 for light along the normal, 0.028 at grazing light. A reflective shadow map's texel reflects
// its light with this share (gi/shaders/rsm_diffuse.glsl), the share the lighting pass shows.
// Midpoint quadrature over `steps` x 2 `steps` view directions.
float integrateSchlickMean(float cosLight, uint32_t steps);

// The table the lighting pass (scale and bias), the GI's lookup (all of it) and the RSMs (the
// Schlick mean) sample: size x size texels,
// cos(view angle) along x and roughness along y, texel (i, j) holding the integral at cosView = i / (size -
// 1), roughness = j / (size - 1) (so both ends are exact under bilinear filtering, as at()).
struct SpecularAlbedoTable {
    static constexpr uint32_t kSize = 32;
    static constexpr uint32_t kSamples = 1024;
    std::vector<SpecularAlbedo> texels; // kSize x kSize, row by row (roughness rows)
    // integrateSchlickMean at cos(light) = i / (kSize - 1).
    std::array<float, kSize> schlickMean{};

    // Bilinear between the texels, as the GPU samples the table.
    SpecularAlbedo at(float cosView, float roughness) const;
    // Linear between the entries.
    float schlickMeanAt(float cosLight) const;
};

// Computed on first use (about 1M samples) and kept for the process.
const SpecularAlbedoTable& specularAlbedoTable();

} // namespace lpv::engine
