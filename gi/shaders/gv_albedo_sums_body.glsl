// The albedo multiple bounces reflect with (gi.bounces > 1): per GV cell the mean albedo of the
// surfels in it, as integer sums a compute pass adds with atomics, so the sums are the same from
// run to run whatever order the invocations run in. The surfels: FROM_CAMERA the finest cascade's
// camera samples (their G-buffer albedo), then FROM_VPLS the sun's VPLs (their flux over a white
// texel's), in one dispatch (a dispatch and its barrier cost llvmpipe more than these few thousand
// invocations do). FROM_POINT, one dispatch per spot or point light RSM: its VPLs' flux over what
// a white block reflects there (the light's intensity, cone and range window times the block's
// solid angle, as rsm_spot.frag lit it): without them a surface that only such a light and no
// camera sees reflected nothing in the further bounces (docs/gi-fidelity.md).
//
// 8 bytes a cell, as the RGBA16F sums this replaces (the console preset has no room for more):
// two R32UI texels, (2 g.x, g.y, g.z) red | green << 16 and (2 g.x + 1, g.y, g.z) count | blue << 16
// (gv_albedo_sums.glsl). 16 bits cannot hold a cell's plain sum (the camera's samples of a near
// wall crowd into a few cells), so the pass runs twice: ALBEDO_PASS 0 counts each cell's
// surfels, 1 adds each surfel's albedo x units / count, where the units leave room for the
// rounding (albedoUnits). A cell's sums are then its mean albedo in those units. The rounding is
// dithered: where thousands of samples of one wall share a cell, each adds only a few units, and
// rounding them all the same way would shift the mean by up to half a unit each (the camera
// against a wall, 14,400 samples in a cell: an albedo up to 0.12 off).
//
// Drawn as points into blended targets (one a camera sample), the camera's albedo took 3.5-4.5 ms
// of the finest cascade's occlusion in the benchmark's atrium on lavapipe, which shades vertices on
// one thread (docs/gi-design.md has the figures of this pass).
#include "gv_common.glsl"
#include "gv_albedo_sums.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#ifdef FROM_VPLS
#include "vpl.glsl"
layout(binding = 1, std430) readonly buffer Vpls {
    Vpl vpls[];
};
#endif
#ifdef FROM_CAMERA
layout(binding = 2) uniform sampler2D gbufferDepth;
layout(binding = 3) uniform sampler2D gbufferNormal;
layout(binding = 5) uniform sampler2D gbufferAlbedo;
#include "camera_samples.glsl"
#endif
layout(binding = 4, r32ui) uniform coherent uimage3D albedoSums;

struct AlbedoSurfel {
    bool valid; // false for an invalid sample, an empty VPL slot, or one outside the volume
    ivec3 cell;
    vec3 albedo;
};

#ifdef FROM_CAMERA
// Camera sample `index` of the grid (camera_samples.glsl).
AlbedoSurfel cameraSurfel(int index) {
    AlbedoSurfel a;
    ivec2 size = textureSize(gbufferDepth, 0);
    int cols = gv.grid.w;
    int rows = max(1, (cols * size.y + size.x / 2) / size.x);
    CameraSample s = cameraSample(ivec2(index % cols, index / cols), cols, rows, size);
    // The RSM's diffuse reflectance (rsm_diffuse.glsl), none for metals (alpha: metallic), without
    // its Schlick mean (at most 2.8%: the angle light arrives at is not known here).
    vec4 base = texelFetch(gbufferAlbedo, s.pixel, 0);
    a.albedo = base.rgb * (1.0 - base.a) * (1.0 - mix(vec3(0.04), base.rgb, base.a));
    a.cell = surfelCell(s.p);
    a.valid = s.valid && insideVolume(a.cell);
    return a;
}
#endif

// Surfel `index`: the first gv.albedoSums.z are the camera's samples, then the VPLs.
AlbedoSurfel surfel(int index) {
#ifdef FROM_CAMERA
    if (index < gv.albedoSums.z) return cameraSurfel(index);
#endif
    index -= gv.albedoSums.z;
    AlbedoSurfel a;
#ifndef FROM_VPLS
    a.valid = false;
    a.cell = ivec3(-1);
    a.albedo = vec3(0.0);
#else
    Vpl v = vpls[min(index, gv.grid.z - 1)];
#ifdef FROM_POINT
    // The cluster's flux over a white block's of its share of texels, lit as rsm_spot.frag lights
    // it: intensity x cone x range window x the block's solid angle x cos^3 off the axis.
    vec3 toSurfel = v.position.xyz - gv.lightPosition.xyz;
    float d2 = max(dot(toSurfel, toSurfel), 1e-8);
    float cosAxis = max(dot(toSurfel * inversesqrt(d2), gv.lightAxis.xyz), 0.0);
    float q = d2 * gv.lightAxis.w;
    float lit = smoothstep(gv.lightDirection.x, gv.lightDirection.y, cosAxis) * clamp(1.0 - q * q, 0.0, 1.0);
    float solidAngle = gv.lightPosition.w * v.normal.w * cosAxis * cosAxis * cosAxis;
    vec3 white = gv.whiteTexelFlux.rgb * (lit * solidAngle);
    // Where the light hardly reaches, the ratio says nothing of the surface.
    bool lightReaches = lit > 1e-3 && solidAngle > 0.0 && max(max(white.r, white.g), white.b) > 0.0;
#else
    // The cluster's flux over what as many white texels would reflect.
    vec3 white = v.flux.w * gv.whiteTexelFlux.rgb;
    bool lightReaches = true;
#endif
    a.albedo = clamp(v.flux.rgb / max(white, vec3(1e-20)), 0.0, 1.0);
    a.cell = surfelCell(v.position.xyz);
    a.valid = index < gv.grid.z && v.position.w > 0.0 && lightReaches && insideVolume(a.cell);
#endif
    return a;
}

void main() {
    AlbedoSurfel a = surfel(int(gl_GlobalInvocationID.x) * gv.albedoSums.y);
    if (!a.valid) return;
    ivec3 rg = ivec3(2 * a.cell.x, a.cell.y, a.cell.z), countBlue = rg + ivec3(1, 0, 0);
    // The pass is a variant, not a uniform: lavapipe specializes a shader on the uniforms its
    // branches test and recompiles it when they change, which it did on each of the two dispatches
    // (about a millisecond each).
#if ALBEDO_PASS == 0
    imageAtomicAdd(albedoSums, countBlue, 1u);
#else
    // The count is final (the first pass is done) while this pass adds blue above it: read it
    // atomically all the same, as the other invocations write the word.
    uint count = imageAtomicOr(albedoSums, countBlue, 0u) & 0xffffu;
    // The dither: the fraction of the surfel's index times the golden ratio (2654435769 / 2^32),
    // spread evenly over [0, 1) for any run of indices, so a cell's errors cancel.
    float dither = float((uint(gl_GlobalInvocationID.x) * 2654435769u) >> 8) / 16777216.0;
    uvec3 add = uvec3(floor(clamp(a.albedo, 0.0, 1.0) * (float(albedoUnits(count)) / float(count)) + dither));
    imageAtomicAdd(albedoSums, rg, add.r | (add.g << 16));
    imageAtomicAdd(albedoSums, countBlue, add.b << 16);
#endif
}
