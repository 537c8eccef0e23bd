// The shipped propagation kernel, included by propagate_<format>.glsl (SH_FORMAT, the packed
// texels that carry a cell's 12 coefficients between iterations, and their packing), compiled
// once per role (gi/CMakeLists.txt). Partial sums come in two layouts (LpvVolumes.h,
// partialSumShell): bounded (n^3: FROM_INJECTION on the first iteration, TO_RESULT on the last,
// cells beyond the border chosen by a select) and, where a coarser cascade hands light in, SHELL
// (a one-cell shell around the volume: SEED before the first iteration, then plain loads). Roles
// are compile-time because a CPU rasterizer runs both sides of a uniform branch.
//
// Why it looks like this (figures in the README):
// - Propagation is linear in the SH coefficients: the five faces a neighbour lights, each
//   evaluated toward its face and re-emitted as a cosine lobe, sum to one sparse 4x4 matrix per
//   direction (constants below, derived in PropagationScheme.h). A neighbour costs 6 multiply-adds
//   per channel instead of five 3-term dots, clamps and lobe updates.
// - Linearity also folds the accumulation into the iteration (Horner's rule): with x the injected
//   volume, y0 = x and y(k+1) = x + P y(k), so y(N) = x + Px + ... + P^N x is the accumulated
//   result. No accumulation texture is read or written until the last iteration stores y(N).
// - SHELL: the partial-sum volumes carry a one-cell shell around the volume, what lies beyond the
//   border. SEED writes y(0) = x inside and the shell once per propagation (nothing, or the
//   coarser cascade's result: the handoff, constant over the iterations), so an iteration reads
//   every neighbour with a plain load, without a bounds test or a select. Choosing the handoff
//   value per load cost 3 trilinear fetches per load on a CPU rasterizer (which evaluates both
//   sides of a select for every lane): 35-37 ms instead of 14-16 per cascade on llvmpipe. The
//   shell costs memory (34^3 instead of 32^3 cells, twice), so a single cascade, which has no
//   handoff and selects a plain zero, keeps the bounded layout: the Xbox 360 budget holds one.
// - Memory operations dominate on every device we measured, so each thread owns a 2x2 column of
//   cells and walks it along z: the z neighbours come from registers, the x/y neighbours inside
//   the 2x2 from registers, and only the 8 cells around it are fetched per step (3 fetched cells
//   per output cell instead of 6). The partial sums travel in as few 32-bit words as the format
//   allows: RGBA8 packed into one RGBA32UI texel, RGBA32F as three RGBA32UI texels of float bits,
//   RGBA16F as three RGBA16F images (one per channel, 6 words per cell either way).
// - On llvmpipe (Mesa 22.3; in-process A/B runs of CPU time, this 2-core machine being noisy):
//   every per-cell read is an imageLoad of a storage image, which llvmpipe compiles to a gather;
//   texelFetch goes through its sampler code and cost 13-20% more of the whole kernel when the
//   kernel read everything that way (an earlier kernel), 18-29% more for the injection volume
//   alone in this one (c4ea6de): only the `_fetch` variants, for devices with 8 storage image
//   bindings, read it so.
//   In the bounded layout out-of-volume cells are chosen with mix(bvec) selects: ?: and && on
//   vectors compile to branches, and a CPU rasterizer runs every branch under lane masks.
// - RGBA16F partial sums used to be packed halves (an RGBA32UI and an RG32UI texel: 2 fetches per
//   cell instead of 3), but Mesa's GL front end lowers packHalf2x16/unpackHalf2x16 to integer
//   code, and on Vulkan too the unpacking cost more than the fetch it saved: as RGBA16F
//   images, converted by llvmpipe's image code, the kernel went from 2.4-2.8x to 3.5-3.9x the
//   baseline on both APIs (same rounding: halves either way).
// - Tried and dropped on llvmpipe: a 4x4 footprint per thread (2 fetched cells per output cell
//   instead of 3) measured the same or slower than 2x2 (register spills eat the saved fetches);
//   carrying part of x in the packed texels (x read with one fetch instead of three) was slower:
//   an image store costs per 32-bit word (llvmpipe stores lane by lane, word by word), and it
//   stored 2 more words per cell than it saved in fetches.
#include "lpv_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#ifdef SLABS
// SLABS: up to four volumes (LpvPropagation::recordTogether's jobs) in one dispatch. Each is a slab
// of the stacked partial sums along z, picked by the workgroup's z; its injection volume, faces,
// handoff and result are its own bindings, chosen by a switch on the slab: uniform over a
// workgroup, so a GPU takes one branch (a CPU rasterizer would run all four: it keeps one dispatch
// per volume, rhi Caps::maskedBranches).
layout(binding = 0, std140) uniform Propagate {
    ivec4 grid; // x: cells per axis, y: cells per thread along z, z: workgroups per slab along z,
                // w: a slab's depth in the partial sums
    vec4 encode[4];  // per slab, as below
    vec4 handoff[4]; // per slab, as below; w 0: no coarser cascade around this slab
} params;
// The volume this workgroup computes: the seed runs one workgroup layer a cell of a slab's depth,
// the iterations params.grid.z workgroups a slab.
#ifdef SEED
#define SLAB (int(gl_WorkGroupID.z) / params.grid.w)
#else
#define SLAB (int(gl_WorkGroupID.z) / params.grid.z)
#endif
#define PARAM_ENCODE params.encode[SLAB]
#define PARAM_HANDOFF params.handoff[SLAB]
#else
layout(binding = 0, std140) uniform Propagate {
    ivec4 grid;  // x: cells per axis, y: cells per thread along z
    // x: rgba8 range (this volume's: LpvVolumes::encodeRange), y: handoff scale (0: none),
    // z: 1 when the coarse volume is encoded
    vec4 encode;
    vec4 handoff; // xyz: the coarse volume's uvw at cell (0,0,0)'s centre; w: uvw per cell
} params;
#define PARAM_ENCODE params.encode
#define PARAM_HANDOFF params.handoff
#endif
#ifdef SLABS
// A slab's set of three SH textures (red, green, blue) at bindings first..first + 2.
#define SLAB_SAMPLERS(name, first) \
    layout(binding = first) uniform sampler3D name##Red; \
    layout(binding = first + 1) uniform sampler3D name##Green; \
    layout(binding = first + 2) uniform sampler3D name##Blue;
#ifdef SEED
// The coarser cascade's result around slabs 0-2 (the last slab is a coarsest cascade or a bounce).
SLAB_SAMPLERS(coarse0, 7)
SLAB_SAMPLERS(coarse1, 10)
SLAB_SAMPLERS(coarse2, 13)
#endif
#elif defined(HANDOFF)
// Cascade handoff (SEED only): outside this volume the neighbours are the next coarser cascade's
// result, so light from beyond the border flows in (Kaplanyan & Dachsbacher 2010).
layout(binding = 20) uniform sampler3D coarseRed;
layout(binding = 21) uniform sampler3D coarseGreen;
layout(binding = 22) uniform sampler3D coarseBlue;
#endif
// Everything the kernel reads cell by cell is a storage image: llvmpipe turns imageLoad into a
// plain gather, where texelFetch goes through its sampler code. That takes up to 10 images, at
// bindings up to 10; where a device has fewer storage image bindings (rhi Caps::
// storageImageBindings: OpenGL guarantees 8, NVIDIA's driver has 8), INJECTED_AS_TEXTURE reads
// the injection volume through texelFetch and the kernel keeps to bindings 1-7.
#ifdef SLABS
// Each slab's injection volume, read through texelFetch (the storage image bindings go to the
// results).
SLAB_SAMPLERS(injected0, 16)
SLAB_SAMPLERS(injected1, 19)
SLAB_SAMPLERS(injected2, 22)
SLAB_SAMPLERS(injected3, 25)
#elif defined(INJECTED_AS_TEXTURE)
layout(binding = 8) uniform sampler3D injectedRed;
layout(binding = 9) uniform sampler3D injectedGreen;
layout(binding = 10) uniform sampler3D injectedBlue;
#define LOAD_INJECTED(volume, k) texelFetch(volume, k, 0)
#else
layout(binding = 8, INJECT_FORMAT) uniform readonly image3D injectedRed;
layout(binding = 9, INJECT_FORMAT) uniform readonly image3D injectedGreen;
layout(binding = 10, INJECT_FORMAT) uniform readonly image3D injectedBlue;
#define LOAD_INJECTED(volume, k) imageLoad(volume, k)
#endif
// The partial sums: packed unsigned-integer texels, or (PARTIALS_AS_SH) one SH_FORMAT image per
// channel like the result.
#ifdef PARTIALS_AS_SH
#define PARTIAL_IMAGE image3D
#define PARTIAL_TEXEL vec4
#else
#define PARTIAL_IMAGE uimage3D
#define PARTIAL_TEXEL uvec4
#endif
// SHELL: partial sums are (n + 2)^3 (odd n: one more); cell c is at c + 1.
#ifdef SEED
// The other partial-sum volume: only its shell is written.
layout(binding = 1, PACKED0_FORMAT) uniform writeonly PARTIAL_IMAGE shell0;
#if PACKED_TEXELS > 1
layout(binding = 2, PACKED1_FORMAT) uniform writeonly PARTIAL_IMAGE shell1;
#endif
#if PACKED_TEXELS > 2
layout(binding = 3, PACKED2_FORMAT) uniform writeonly PARTIAL_IMAGE shell2;
#endif
#elif !defined(FROM_INJECTION)
layout(binding = 1, PACKED0_FORMAT) uniform readonly PARTIAL_IMAGE src0;
#if PACKED_TEXELS > 1
layout(binding = 2, PACKED1_FORMAT) uniform readonly PARTIAL_IMAGE src1;
#endif
#if PACKED_TEXELS > 2
layout(binding = 3, PACKED2_FORMAT) uniform readonly PARTIAL_IMAGE src2;
#endif
#endif
#if defined(TO_RESULT) && defined(SLABS)
#define SLAB_RESULT(s, first) \
    layout(binding = first, SH_FORMAT) uniform writeonly image3D result##s##Red; \
    layout(binding = first + 1, SH_FORMAT) uniform writeonly image3D result##s##Green; \
    layout(binding = first + 2, SH_FORMAT) uniform writeonly image3D result##s##Blue;
SLAB_RESULT(0, 4)
SLAB_RESULT(1, 7)
SLAB_RESULT(2, 10)
SLAB_RESULT(3, 13)
#elif defined(TO_RESULT)
layout(binding = 4, SH_FORMAT) uniform writeonly image3D resultRed;
layout(binding = 5, SH_FORMAT) uniform writeonly image3D resultGreen;
layout(binding = 6, SH_FORMAT) uniform writeonly image3D resultBlue;
#else
layout(binding = 4, PACKED0_FORMAT) uniform writeonly PARTIAL_IMAGE dst0;
#if PACKED_TEXELS > 1
layout(binding = 5, PACKED1_FORMAT) uniform writeonly PARTIAL_IMAGE dst1;
#endif
#if PACKED_TEXELS > 2
layout(binding = 6, PACKED2_FORMAT) uniform writeonly PARTIAL_IMAGE dst2;
#endif
#endif

#if defined(OCCLUSION) && defined(SLABS)
// Per cell: the transmittance of its -x, -y, -z faces (GeometryVolume), each slab's own.
layout(binding = 28) uniform sampler3D faceTransmittance0;
layout(binding = 29) uniform sampler3D faceTransmittance1;
layout(binding = 30) uniform sampler3D faceTransmittance2;
layout(binding = 31) uniform sampler3D faceTransmittance3;
#elif defined(OCCLUSION)
// Per cell: the transmittance of its -x, -y, -z faces (GeometryVolume).
layout(binding = 7, rgba8) uniform readonly image3D faceTransmittance;
#endif

struct Sh3 {
    vec4 r, g, b;
};
// Defined by the format's .comp file.
vec4 encodeSh(vec4 v);
Sh3 unpackCell(PARTIAL_TEXEL t0, PARTIAL_TEXEL t1, PARTIAL_TEXEL t2);
void packCell(Sh3 v, out PARTIAL_TEXEL t0, out PARTIAL_TEXEL t1, out PARTIAL_TEXEL t2);

// The transfer from a neighbour one cell away along axis e: KA..KE.
#include "propagation_transfer.glsl"

// Coefficient order (Y00, y, z, x): x is [3], y is [1], z is [2].
vec4 transferX(vec4 p, vec4 m) {
    return vec4(KA * (p.x + m.x) + KB * (p.w - m.w), KE * (p.y + m.y), KE * (p.z + m.z),
                KC * (p.x - m.x) + KD * (p.w + m.w));
}
vec4 transferY(vec4 p, vec4 m) {
    return vec4(KA * (p.x + m.x) + KB * (p.y - m.y), KC * (p.x - m.x) + KD * (p.y + m.y), KE * (p.z + m.z),
                KE * (p.w + m.w));
}
vec4 transferZ(vec4 p, vec4 m) {
    return vec4(KA * (p.x + m.x) + KB * (p.z - m.z), KE * (p.y + m.y), KC * (p.x - m.x) + KD * (p.z + m.z),
                KE * (p.w + m.w));
}

Sh3 scale(Sh3 a, float k) { return Sh3(a.r * k, a.g * k, a.b * k); }

// What a cell receives from its six neighbours (mx: the neighbour at cell - x, px: at cell + x...),
// each attenuated by the face it crosses: `lower` holds the cell's own -x, -y, -z faces, `upper`
// the +x, +y, +z ones (the next cells' lower faces). Linear still: the factors do not depend on
// the light.
Sh3 gather(Sh3 mx, Sh3 px, Sh3 my, Sh3 py, Sh3 mz, Sh3 pz, vec3 lower, vec3 upper) {
#ifdef OCCLUSION
    mx = scale(mx, lower.x), px = scale(px, upper.x), my = scale(my, lower.y), py = scale(py, upper.y);
    mz = scale(mz, lower.z), pz = scale(pz, upper.z);
#endif
    Sh3 o;
    o.r = transferX(mx.r, px.r) + transferY(my.r, py.r) + transferZ(mz.r, pz.r);
    o.g = transferX(mx.g, px.g) + transferY(my.g, py.g) + transferZ(mz.g, pz.g);
    o.b = transferX(mx.b, px.b) + transferY(my.b, py.b) + transferZ(mz.b, pz.b);
    return o;
}

Sh3 add(Sh3 a, Sh3 b) { return Sh3(a.r + b.r, a.g + b.g, a.b + b.b); }

// A cell outside the volume: the coarser cascade's result there, in this cascade's units (the
// intensity of a cell scales with its cross-section), or nothing for the coarsest cascade.
Sh3 outside(ivec3 c) {
#if defined(SLABS) && defined(SEED)
    const vec3 uvw = PARAM_HANDOFF.xyz + vec3(c) * PARAM_HANDOFF.w;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    if (PARAM_HANDOFF.w == 0.0) return Sh3(r, g, b);
#define SAMPLE_COARSE(name) \
    r = textureLod(name##Red, uvw, 0.0), g = textureLod(name##Green, uvw, 0.0), b = textureLod(name##Blue, uvw, 0.0)
    switch (SLAB) {
    case 0:
        SAMPLE_COARSE(coarse0);
        break;
    case 1:
        SAMPLE_COARSE(coarse1);
        break;
    default:
        SAMPLE_COARSE(coarse2);
        break;
    }
    // Float volumes only (rgba8 keeps one set, LpvSettings::propagateTogether): nothing to decode.
    return Sh3(r * PARAM_ENCODE.y, g * PARAM_ENCODE.y, b * PARAM_ENCODE.y);
#elif !defined(HANDOFF)
    return Sh3(vec4(0.0), vec4(0.0), vec4(0.0));
#else
    const vec3 uvw = params.handoff.xyz + vec3(c) * params.handoff.w;
    vec4 r = textureLod(coarseRed, uvw, 0.0), g = textureLod(coarseGreen, uvw, 0.0);
    vec4 b = textureLod(coarseBlue, uvw, 0.0);
    if (params.encode.z != 0.0) {
        // In the coarser cascade's range: the same radiance over cells of 1 / encode.y the area.
        float coarseRange = params.encode.x / params.encode.y;
        r = decodeShRange(r, coarseRange), g = decodeShRange(g, coarseRange), b = decodeShRange(b, coarseRange);
    }
    return Sh3(r * params.encode.y, g * params.encode.y, b * params.encode.y);
#endif
}

#if !defined(SEED) && !defined(FROM_INJECTION)
// The previous iteration's partial sum at texel k of the partial-sum volumes.
Sh3 loadPartial(ivec3 k) {
#ifdef SLABS
    k.z += SLAB * params.grid.w;
#endif
    PARTIAL_TEXEL t0 = imageLoad(src0, k), t1 = PARTIAL_TEXEL(0), t2 = PARTIAL_TEXEL(0);
#if PACKED_TEXELS > 1
    t1 = imageLoad(src1, k);
#endif
#if PACKED_TEXELS > 2
    t2 = imageLoad(src2, k);
#endif
    return unpackCell(t0, t1, t2);
}
#endif

#ifdef SHELL
// The injection volume at a cell inside the volume (clamped: with an odd n the 2x2 column may stick
// out, and storeCell drops those cells).
Sh3 loadInjected(ivec3 c, int n) {
    const ivec3 k = min(c, ivec3(n - 1));
#ifdef SLABS
#define FETCH_INJECTED(name) Sh3(texelFetch(name##Red, k, 0), texelFetch(name##Green, k, 0), texelFetch(name##Blue, k, 0))
    switch (SLAB) {
    case 0:
        return FETCH_INJECTED(injected0);
    case 1:
        return FETCH_INJECTED(injected1);
    case 2:
        return FETCH_INJECTED(injected2);
    default:
        return FETCH_INJECTED(injected3);
    }
#else
    return Sh3(LOAD_INJECTED(injectedRed, k), LOAD_INJECTED(injectedGreen, k), LOAD_INJECTED(injectedBlue, k));
#endif
}

#ifndef SEED
// The previous iteration's partial sum at a cell, or the shell's value one cell beyond the volume.
Sh3 loadSource(ivec3 c, int n) { return loadPartial(c + 1); }
#endif
#else
// Bounded: beyond the volume a cell reads outside(); the coordinate is clamped first so that no
// access is ever out of range, and the choice is a select (mix with a bvec), not a branch: a CPU
// rasterizer runs every branch with lane masks, and ?: or && on vectors compile to branches.
Sh3 insideOr(ivec3 c, ivec3 k, Sh3 v) {
    const bvec4 inside = bvec4(all(equal(c, k)));
    const Sh3 o = outside(c);
    return Sh3(mix(o.r, v.r, inside), mix(o.g, v.g, inside), mix(o.b, v.b, inside));
}

// The injection volume at a cell, or outside() beyond the volume.
Sh3 loadInjected(ivec3 c, int n) {
    const ivec3 k = clamp(c, ivec3(0), ivec3(n - 1));
    return insideOr(c, k, Sh3(LOAD_INJECTED(injectedRed, k), LOAD_INJECTED(injectedGreen, k), LOAD_INJECTED(injectedBlue, k)));
}

// The previous iteration's partial sum at a cell (outside() beyond the volume).
Sh3 loadSource(ivec3 c, int n) {
#ifdef FROM_INJECTION
    return loadInjected(c, n);
#else
    const ivec3 k = clamp(c, ivec3(0), ivec3(n - 1));
    return insideOr(c, k, loadPartial(k));
#endif
}
#endif

// Stores packed texels t0..t2 at p in the partial-sum images NAME0..NAME2 (as many as the format has).
#if PACKED_TEXELS > 2
#define STORE_PACKED(NAME, p, t0, t1, t2) \
    imageStore(NAME##0, p, t0), imageStore(NAME##1, p, t1), imageStore(NAME##2, p, t2)
#elif PACKED_TEXELS > 1
#define STORE_PACKED(NAME, p, t0, t1, t2) imageStore(NAME##0, p, t0), imageStore(NAME##1, p, t1)
#else
#define STORE_PACKED(NAME, p, t0, t1, t2) imageStore(NAME##0, p, t0)
#endif

void storePartial(ivec3 p, Sh3 v) {
#ifndef TO_RESULT
#ifdef SLABS
    p.z += SLAB * params.grid.w;
#endif
    PARTIAL_TEXEL t0, t1, t2;
    packCell(v, t0, t1, t2);
    STORE_PACKED(dst, p, t0, t1, t2);
#endif
}

void storeCell(ivec3 c, int n, Sh3 v) {
    if (any(greaterThanEqual(c, ivec3(n)))) return; // odd sizes: the 2x2 column may stick out
#if defined(TO_RESULT) && defined(SLABS)
#define SLAB_STORE_RESULT(s) \
    imageStore(result##s##Red, c, encodeSh(v.r)), imageStore(result##s##Green, c, encodeSh(v.g)), \
        imageStore(result##s##Blue, c, encodeSh(v.b))
    switch (SLAB) {
    case 0:
        SLAB_STORE_RESULT(0);
        break;
    case 1:
        SLAB_STORE_RESULT(1);
        break;
    case 2:
        SLAB_STORE_RESULT(2);
        break;
    default:
        SLAB_STORE_RESULT(3);
        break;
    }
#elif defined(TO_RESULT)
    imageStore(resultRed, c, encodeSh(v.r));
    imageStore(resultGreen, c, encodeSh(v.g));
    imageStore(resultBlue, c, encodeSh(v.b));
#else
#ifdef SHELL
    storePartial(c + 1, v);
#else
    storePartial(c, v);
#endif
#endif
}

// Face transmittance of a cell; 1 outside the volume (nothing comes from there anyway).
vec3 faces(ivec3 c, int n) {
#if defined(OCCLUSION) && defined(SLABS)
    const ivec3 k = clamp(c, ivec3(0), ivec3(n - 1));
    vec3 t;
    switch (SLAB) {
    case 0:
        t = texelFetch(faceTransmittance0, k, 0).xyz;
        break;
    case 1:
        t = texelFetch(faceTransmittance1, k, 0).xyz;
        break;
    case 2:
        t = texelFetch(faceTransmittance2, k, 0).xyz;
        break;
    default:
        t = texelFetch(faceTransmittance3, k, 0).xyz;
        break;
    }
    return mix(vec3(1.0), t, bvec3(all(equal(c, k))));
#elif defined(OCCLUSION)
    const ivec3 k = clamp(c, ivec3(0), ivec3(n - 1));
    return mix(vec3(1.0), imageLoad(faceTransmittance, k).xyz, bvec3(all(equal(c, k))));
#else
    return vec3(1.0);
#endif
}

#ifdef SEED
// y(0) = x inside the volume and the shell around it, in both partial-sum volumes; one thread per
// cell of the padded volume.
void main() {
    const int n = params.grid.x;
    ivec3 p = ivec3(gl_GlobalInvocationID);
#ifdef SLABS
    p.z -= SLAB * params.grid.w;
#endif
    if (any(greaterThanEqual(p, ivec3(n + 2 + (n & 1))))) return;
    const ivec3 c = p - 1;
    if (all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(n)))) {
        storePartial(p, loadInjected(c, n));
        return;
    }
    // Beyond the border: the same texels in both partial-sum volumes.
    PARTIAL_TEXEL t0, t1, t2;
    packCell(outside(c), t0, t1, t2);
#ifdef SLABS
    p.z += SLAB * params.grid.w;
#endif
    STORE_PACKED(dst, p, t0, t1, t2);
    STORE_PACKED(shell, p, t0, t1, t2);
}
#else
void main() {
    const int n = params.grid.x;
    const ivec2 o = ivec2(gl_GlobalInvocationID.xy) * 2; // the 2x2 column: o, o+x, o+y, o+x+y
#ifdef SLABS
    const int z0 = (int(gl_WorkGroupID.z) - SLAB * params.grid.z) * params.grid.y;
#else
    const int z0 = int(gl_GlobalInvocationID.z) * params.grid.y;
#endif
    if (o.x >= n || o.y >= n || z0 >= n) return;
    const int z1 = min(z0 + params.grid.y, n);
    // The column's cells below, at and above the current slice: 0 = (0,0), 1 = (1,0), 2 = (0,1),
    // 3 = (1,1) relative to o.
    Sh3 below0 = loadSource(ivec3(o, z0 - 1), n), below1 = loadSource(ivec3(o + ivec2(1, 0), z0 - 1), n);
    Sh3 below2 = loadSource(ivec3(o + ivec2(0, 1), z0 - 1), n), below3 = loadSource(ivec3(o + ivec2(1, 1), z0 - 1), n);
    Sh3 at0 = loadSource(ivec3(o, z0), n), at1 = loadSource(ivec3(o + ivec2(1, 0), z0), n);
    Sh3 at2 = loadSource(ivec3(o + ivec2(0, 1), z0), n), at3 = loadSource(ivec3(o + ivec2(1, 1), z0), n);
    vec3 face0 = faces(ivec3(o, z0), n), face1 = faces(ivec3(o + ivec2(1, 0), z0), n);
    vec3 face2 = faces(ivec3(o + ivec2(0, 1), z0), n), face3 = faces(ivec3(o + ivec2(1, 1), z0), n);
    for (int z = z0; z < z1; ++z) {
        const Sh3 above0 = loadSource(ivec3(o, z + 1), n), above1 = loadSource(ivec3(o + ivec2(1, 0), z + 1), n);
        const Sh3 above2 = loadSource(ivec3(o + ivec2(0, 1), z + 1), n);
        const Sh3 above3 = loadSource(ivec3(o + ivec2(1, 1), z + 1), n);
        // The ring around the column in this slice: left, right, bottom (-y) and top (+y).
        const Sh3 left0 = loadSource(ivec3(o + ivec2(-1, 0), z), n), left2 = loadSource(ivec3(o + ivec2(-1, 1), z), n);
        const Sh3 right1 = loadSource(ivec3(o + ivec2(2, 0), z), n), right3 = loadSource(ivec3(o + ivec2(2, 1), z), n);
        const Sh3 bottom0 = loadSource(ivec3(o + ivec2(0, -1), z), n);
        const Sh3 bottom1 = loadSource(ivec3(o + ivec2(1, -1), z), n);
        const Sh3 top2 = loadSource(ivec3(o + ivec2(0, 2), z), n), top3 = loadSource(ivec3(o + ivec2(1, 2), z), n);

        const vec3 faceAbove0 = faces(ivec3(o, z + 1), n), faceAbove1 = faces(ivec3(o + ivec2(1, 0), z + 1), n);
        const vec3 faceAbove2 = faces(ivec3(o + ivec2(0, 1), z + 1), n);
        const vec3 faceAbove3 = faces(ivec3(o + ivec2(1, 1), z + 1), n);
        const vec3 faceRight1 = faces(ivec3(o + ivec2(2, 0), z), n), faceRight3 = faces(ivec3(o + ivec2(2, 1), z), n);
        const vec3 faceTop2 = faces(ivec3(o + ivec2(0, 2), z), n), faceTop3 = faces(ivec3(o + ivec2(1, 2), z), n);

        Sh3 out0 = gather(left0, at1, bottom0, at2, below0, above0, face0, vec3(face1.x, face2.y, faceAbove0.z));
        Sh3 out1 = gather(at0, right1, bottom1, at3, below1, above1, face1, vec3(faceRight1.x, face3.y, faceAbove1.z));
        Sh3 out2 = gather(left2, at3, at0, top2, below2, above2, face2, vec3(face3.x, faceTop2.y, faceAbove2.z));
        Sh3 out3 = gather(at2, right3, at1, top3, below3, above3, face3, vec3(faceRight3.x, faceTop3.y, faceAbove3.z));
        // + x: on a bounded first iteration the source is x itself; otherwise it is read from the
        // injection.
#ifdef FROM_INJECTION
        out0 = add(out0, at0), out1 = add(out1, at1), out2 = add(out2, at2), out3 = add(out3, at3);
#else
        out0 = add(out0, loadInjected(ivec3(o, z), n));
        out1 = add(out1, loadInjected(ivec3(o + ivec2(1, 0), z), n));
        out2 = add(out2, loadInjected(ivec3(o + ivec2(0, 1), z), n));
        out3 = add(out3, loadInjected(ivec3(o + ivec2(1, 1), z), n));
#endif
        storeCell(ivec3(o, z), n, out0);
        storeCell(ivec3(o + ivec2(1, 0), z), n, out1);
        storeCell(ivec3(o + ivec2(0, 1), z), n, out2);
        storeCell(ivec3(o + ivec2(1, 1), z), n, out3);

        below0 = at0, below1 = at1, below2 = at2, below3 = at3;
        at0 = above0, at1 = above1, at2 = above2, at3 = above3;
        face0 = faceAbove0, face1 = faceAbove1, face2 = faceAbove2, face3 = faceAbove3;
    }
}
#endif
