// The normal an indirect provider stores in the glossy target's alpha for the lighting pass's
// rebuild (engine/render/IndirectLighting.h), so the rebuild needs no fetch of the G-buffer's
// normals: octahedral coordinates on a 64 x 64 grid, as one integer from -2048 to 2047, which a
// half float holds exactly (integers up to 2048 in magnitude). The grid's step is about 1.3 degrees
// at most, where the rebuild's normal weight (cos^16) changes by under 0.5%.
#ifndef REBUILD_NORMAL_GLSL
#define REBUILD_NORMAL_GLSL

float packRebuildNormal(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 o = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    ivec2 q = clamp(ivec2(round((o * 0.5 + 0.5) * 63.0)), ivec2(0), ivec2(63));
    return float(q.y * 64 + q.x - 2048);
}

vec3 unpackRebuildNormal(float packed) {
    int k = int(packed) + 2048;
    vec2 o = vec2(k & 63, k >> 6) / 63.0 * 2.0 - 1.0;
    vec3 n = vec3(o, 1.0 - abs(o.x) - abs(o.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

#endif
