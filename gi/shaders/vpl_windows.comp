#version 450
#extension GL_GOOGLE_include_directive : require
// The sun's gather VPLs of one cascade that each window of the gather can take, listed per phase
// (gi/VplWindows.h): a texel of phase (x, y) sums the clusters (x, y) mod 4, and of those it keeps
// only the lit ones of its window (vpl_gather.frag). Walking the whole grid, a texel read every
// slot of every gathered cascade, though most are unlit (past the scene's edge) or in another
// cascade's box. Each list keeps the grid's order, so the gather adds what it adds in the same
// order as from the grid. One workgroup per phase and window.
#include "cascade_region.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

#include "vpl.glsl"

layout(binding = 0, std140) uniform Params {
    vec4 within;  // window 0 and 1: the box (xyz corner, w cell size) the VPL lies in; w 0: any
    vec4 beyond;  // window 1: the box it lies outside; w 0: window 1 takes none
    ivec4 sizes;  // x: the cluster grid's side, y: cells per cascade axis, z: a list's room
} params;
layout(binding = 1, std430) readonly buffer Vpls { Vpl vpls[]; };
// counts[16 window + phase]; the list of phase p in window w at slots[(16 w + p) room].
layout(binding = 2, std430) writeonly buffer Windows {
    uint counts[32];
    uint slots[];
} windows;

// Within or beyond a box by a thousandth of a cell more than the gather's own test: a list may
// hold a VPL the gather then leaves (it tests every one again) but never lacks one it takes.
bool inBox(vec4 box, vec3 p, float margin) {
    vec3 uvw = uvwInVolume(box, params.sizes.y, p);
    float m = margin / float(params.sizes.y);
    return all(greaterThanEqual(uvw, vec3(-m))) && all(lessThanEqual(uvw, vec3(1.0 + m)));
}

bool takes(int window, Vpl v) {
    if (v.position.w < 1e-30) return false; // unlit (vpl_gather.frag's step(1e-30, w)); NaN stays
    vec3 p = v.position.xyz;
    if (params.within.w > 0.0 && !inBox(params.within, p, 1e-3)) return false;
    return window == 0 || (params.beyond.w > 0.0 && !inBox(params.beyond, p, -1e-3));
}

shared uint sums[64];

void main() {
    int phase = int(gl_WorkGroupID.x), window = int(gl_WorkGroupID.y);
    ivec2 first = ivec2(phase & 3, phase >> 2);
    int side = params.sizes.x;
    uint room = uint(params.sizes.z);
    uint list = uint(16 * window + phase) * room;
    ivec2 cells = max((ivec2(side) - first + 3) / 4, ivec2(0)); // this phase's clusters per axis
    int clusters = cells.x * cells.y;
    uint count = 0u;
    uint t = gl_LocalInvocationID.x;
    for (int base = 0; base < clusters; base += 64) {
        // Thread t's cluster, in the grid's order; two slots each.
        int j = base + int(t);
        uint mine = 0u;
        uint slot = 0u;
        if (j < clusters) {
            ivec2 c = first + 4 * ivec2(j % cells.x, j / cells.x);
            slot = uint(2 * (c.y * side + c.x));
            mine = (takes(window, vpls[slot]) ? 1u : 0u) | (takes(window, vpls[slot + 1u]) ? 2u : 0u);
        }
        // An inclusive prefix sum of the slots taken (Hillis-Steele), then each thread writes its own.
        uint taken = bitCount(mine);
        sums[t] = taken;
        barrier();
        for (uint d = 1u; d < 64u; d <<= 1) {
            uint add = t >= d ? sums[t - d] : 0u;
            barrier();
            sums[t] += add;
            barrier();
        }
        uint at = count + sums[t] - taken;
        if ((mine & 1u) != 0u) windows.slots[list + at++] = slot;
        if ((mine & 2u) != 0u) windows.slots[list + at] = slot + 1u;
        count += sums[63];
        barrier();
    }
    if (t == 0u) windows.counts[16 * window + phase] = count;
}
