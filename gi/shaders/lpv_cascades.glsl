// The cascades' result volumes as the fullscreen GI passes sample them (lpv_lookup.glsl,
// lpv_glossy.glsl): cascade c's R, G, B volumes at bindings 3 + 3c .. 5 + 3c (unused cascades bound
// to the coarsest), and the SH of each channel at a point integrated against a lobe.
#ifndef LPV_CASCADES_GLSL
#define LPV_CASCADES_GLSL

#include "cascade_region.glsl"
#include "lpv_common.glsl"

layout(binding = 3) uniform sampler3D lpv0r;
layout(binding = 4) uniform sampler3D lpv0g;
layout(binding = 5) uniform sampler3D lpv0b;
layout(binding = 6) uniform sampler3D lpv1r;
layout(binding = 7) uniform sampler3D lpv1g;
layout(binding = 8) uniform sampler3D lpv1b;
layout(binding = 9) uniform sampler3D lpv2r;
layout(binding = 10) uniform sampler3D lpv2g;
layout(binding = 11) uniform sampler3D lpv2b;
layout(binding = 12) uniform sampler3D lpv3r;
layout(binding = 13) uniform sampler3D lpv3g;
layout(binding = 14) uniform sampler3D lpv3b;

// `range` > 0: the volumes are rgba8, range-encoded. The volumes have one mip, and an explicit
// LOD spares llvmpipe the per-quad derivatives an implicit one computes (undefined anyway inside
// the march's and the lookup's per-texel branches): interleaved runs, the atrium's lookup 9% and
// glossy march 3-8% faster, the same texels.
vec3 projectVolumes(sampler3D r, sampler3D g, sampler3D b, vec3 uvw, vec4 lobe, float range) {
    vec4 sr = textureLod(r, uvw, 0.0), sg = textureLod(g, uvw, 0.0), sb = textureLod(b, uvw, 0.0);
    if (range > 0.0) sr = decodeShRange(sr, range), sg = decodeShRange(sg, range), sb = decodeShRange(sb, range);
    return vec3(dot(sr, lobe), dot(sg, lobe), dot(sb, lobe));
}

// Cascade c's intensity at uvw weighted by `lobe`, per channel. Call it with a constant c: a
// cascade chosen per pixel at run time makes a CPU rasterizer fetch every cascade's volumes.
vec3 projectCascade(int c, vec3 uvw, vec4 lobe, float range) {
    if (c == 0) return projectVolumes(lpv0r, lpv0g, lpv0b, uvw, lobe, range);
    if (c == 1) return projectVolumes(lpv1r, lpv1g, lpv1b, uvw, lobe, range);
    if (c == 2) return projectVolumes(lpv2r, lpv2g, lpv2b, uvw, lobe, range);
    return projectVolumes(lpv3r, lpv3g, lpv3b, uvw, lobe, range);
}

// Cascade c's intensity at uvw, each channel weighted by its own lobe (the glossy march).
vec3 projectVolumesPerChannel(sampler3D r, sampler3D g, sampler3D b, vec3 uvw, vec4 lobeR, vec4 lobeG,
                              vec4 lobeB, float range) {
    vec4 sr = textureLod(r, uvw, 0.0), sg = textureLod(g, uvw, 0.0), sb = textureLod(b, uvw, 0.0);
    if (range > 0.0) sr = decodeShRange(sr, range), sg = decodeShRange(sg, range), sb = decodeShRange(sb, range);
    return vec3(dot(sr, lobeR), dot(sg, lobeG), dot(sb, lobeB));
}

vec3 projectCascadePerChannel(int c, vec3 uvw, vec4 lobeR, vec4 lobeG, vec4 lobeB, float range) {
    if (c == 0) return projectVolumesPerChannel(lpv0r, lpv0g, lpv0b, uvw, lobeR, lobeG, lobeB, range);
    if (c == 1) return projectVolumesPerChannel(lpv1r, lpv1g, lpv1b, uvw, lobeR, lobeG, lobeB, range);
    if (c == 2) return projectVolumesPerChannel(lpv2r, lpv2g, lpv2b, uvw, lobeR, lobeG, lobeB, range);
    return projectVolumesPerChannel(lpv3r, lpv3g, lpv3b, uvw, lobeR, lobeG, lobeB, range);
}

// The lookup's two answers from one fetch of each volume: the irradiance (one lobe for every
// channel) and the glossy radiance (each channel its own lobe: the lobe's mean direction depends
// on the channel's F0).
struct CascadeSample {
    vec3 irradiance;
    vec3 glossy;
};

struct LookupLobes {
    vec4 irradiance;
    vec4 glossyR, glossyG, glossyB;
};

CascadeSample sampleVolumes(sampler3D r, sampler3D g, sampler3D b, vec3 uvw, LookupLobes lobes, float range) {
    vec4 sr = textureLod(r, uvw, 0.0), sg = textureLod(g, uvw, 0.0), sb = textureLod(b, uvw, 0.0);
    if (range > 0.0) sr = decodeShRange(sr, range), sg = decodeShRange(sg, range), sb = decodeShRange(sb, range);
    return CascadeSample(vec3(dot(sr, lobes.irradiance), dot(sg, lobes.irradiance), dot(sb, lobes.irradiance)),
                         vec3(dot(sr, lobes.glossyR), dot(sg, lobes.glossyG), dot(sb, lobes.glossyB)));
}

// As projectCascade, both answers.
CascadeSample sampleCascade(int c, vec3 uvw, LookupLobes lobes, float range) {
    if (c == 0) return sampleVolumes(lpv0r, lpv0g, lpv0b, uvw, lobes, range);
    if (c == 1) return sampleVolumes(lpv1r, lpv1g, lpv1b, uvw, lobes, range);
    if (c == 2) return sampleVolumes(lpv2r, lpv2g, lpv2b, uvw, lobes, range);
    return sampleVolumes(lpv3r, lpv3g, lpv3b, uvw, lobes, range);
}

#endif
