// Analytic point and spot lights, added already propagated to the accumulated volume (included by
// point_lights_<format>.comp, which defines SH_FORMAT). The formula and its derivation are in
// gi/include/gi/AnalyticLight.h; gi/src/AnalyticLight.cpp is the same formula on the CPU.
//
// One thread per cell and all three colour channels; a group is a 4x4x4 block of cells. A light
// reaches a small part of the volume, and llvmpipe runs a masked-off branch anyway, so the group
// first marks the lights whose range reaches its block (a bit mask in shared memory: the order of
// the lights, and so the sums, do not depend on thread timing), then every thread loops over the
// marked lights only (about 8x less work than every light for every cell at 1024 lights). The
// lights are a uniform block (48 KiB; desktop drivers and Mesa allow 64 KiB): read at an index the
// whole group shares, llvmpipe loads them once instead of per thread as from a storage buffer (3x
// faster). Sums stay in registers; a cell no light reaches gets no image traffic.
#include "lpv_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

const uint MAX_LIGHTS = 1024;  // PointLightInjection::kMaxLights

struct AnalyticLight {
    vec4 positionInvRange2;  // xyz: position; w: 1 / range^2, 0 for an infinite range
    vec4 intensityCos;       // rgb: radiant intensity x gi.intensity; w: cos(outer cone)
    vec4 spotCos;            // xyz: spot direction; w: cos(inner cone)
};

layout(binding = 0, std140) uniform PointLights {
    vec4 gridOrigin;  // xyz: corner of cell 0; w: cell size
    ivec4 grid;       // x: cells per axis, y: light count, z: 0 (the count's index offset)
    vec4 encode;      // x: this cascade's rgba8 range (LpvVolumes::encodeRange)
} params;
layout(binding = 1, std140) uniform Lights {
    AnalyticLight lights[MAX_LIGHTS];
};
layout(binding = 2, SH_FORMAT) uniform image3D accRed;
layout(binding = 3, SH_FORMAT) uniform image3D accGreen;
layout(binding = 4, SH_FORMAT) uniform image3D accBlue;

shared uint reaching[MAX_LIGHTS / 32];

#include "result_sh.glsl"
vec4 encodeSh(vec4 v) { return storeResultSh(v, params.encode.x); }
vec4 decodeSh(vec4 v) { return loadResultSh(v, params.encode.x); }

// One light at one cell centre (`k` = s^2 / pi): the formula of gi/AnalyticLight.h, or nothing.
bool addLight(AnalyticLight l, vec3 centre, float halfCell, float k, inout vec4 r, inout vec4 g, inout vec4 b) {
    vec3 toCell = centre - l.positionInvRange2.xyz;
    // The light's own cell: isotropic there, no direction of arrival (and d -> 0).
    if (all(lessThan(abs(toCell), vec3(halfCell)))) return false;
    float d2 = dot(toCell, toCell);
    float q = d2 * l.positionInvRange2.w;  // (d / range)^2
    if (q >= 1.0) return false;
    float invD = inversesqrt(d2);
    vec3 w = toCell * invD;
    float spot = smoothstep(l.intensityCos.w, l.spotCos.w, dot(w, l.spotCos.xyz));
    // Flux through the cell's cross-section (s^2 / d^2 sr of the light, in the range window), as
    // a cosine lobe of intensity flux / pi along w.
    vec4 lobe = shCosineLobe(w) * (spot * (1.0 - q * q) * k * invD * invD);
    r += lobe * l.intensityCos.r;
    g += lobe * l.intensityCos.g;
    b += lobe * l.intensityCos.b;
    return true;
}

void main() {
    int n = params.grid.x;
    // The count at an index the compiler cannot fold (grid.z is 0): lavapipe specializes a shader
    // on the uniforms its loops and branches test, and re-specialized this one for each cascade's
    // count, on every frame (0.8-1.5 ms each time).
    uint count = uint(params.grid[1 + params.grid.z]);
    float s = params.gridOrigin.w;
    // Mark the lights whose range reaches this group's block of cells.
    uint local = gl_LocalInvocationIndex;
    uint threads = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;
    for (uint word = local; word < MAX_LIGHTS / 32; word += threads) reaching[word] = 0u;
    barrier();
    vec3 blockMin = params.gridOrigin.xyz + vec3(gl_WorkGroupID * gl_WorkGroupSize) * s;
    vec3 blockMax = blockMin + vec3(gl_WorkGroupSize) * s;
    for (uint i = local; i < count; i += threads) {
        vec4 p = lights[i].positionInvRange2;
        vec3 outside = p.xyz - clamp(p.xyz, blockMin, blockMax);
        if (dot(outside, outside) * p.w < 1.0) atomicOr(reaching[i / 32u], 1u << (i % 32u));
    }
    barrier();

    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(cell, ivec3(n)))) return;
    vec3 centre = params.gridOrigin.xyz + (vec3(cell) + 0.5) * s;
    float halfCell = 0.5 * s, k = s * s / PI;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    bool reached = false;
    for (uint word = 0u; word < (count + 31u) / 32u; ++word) {
        // The same bits in every thread of the group: a loop the whole group runs alike.
        uint bits = reaching[word];
        while (bits != 0u) {
            int bit = findLSB(bits);
            bits &= bits - 1u;
            if (addLight(lights[word * 32u + uint(bit)], centre, halfCell, k, r, g, b)) reached = true;
        }
    }
    if (!reached) return;
    imageStore(accRed, cell, encodeSh(decodeSh(imageLoad(accRed, cell)) + r));
    imageStore(accGreen, cell, encodeSh(decodeSh(imageLoad(accGreen, cell)) + g));
    imageStore(accBlue, cell, encodeSh(decodeSh(imageLoad(accBlue, cell)) + b));
}
