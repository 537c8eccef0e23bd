// Propagation for RGBA16F volumes. The partial sums travel as 12 halves per cell in an RGBA32UI
// and an RG32UI texel: two fetches per neighbour instead of three, at the same precision.
#define SH_FORMAT rgba16f
#define PACKED_TEXELS 2
#define PACKED0_FORMAT rgba32ui
#define PACKED1_FORMAT rg32ui
#define INJECT_FORMAT rgba16f // the injection volume (LpvVolumes.cpp)
#include "propagate_body.glsl"

vec4 encodeSh(vec4 v) { return v; }

vec4 unpackHalves(uint a, uint b) { return vec4(unpackHalf2x16(a), unpackHalf2x16(b)); }
Sh3 unpackCell(uvec4 t0, uvec4 t1, uvec4 t2) {
    return Sh3(unpackHalves(t0.x, t0.y), unpackHalves(t0.z, t0.w), unpackHalves(t1.x, t1.y));
}
void packCell(Sh3 v, out uvec4 t0, out uvec4 t1, out uvec4 t2) {
    t0 = uvec4(packHalf2x16(v.r.xy), packHalf2x16(v.r.zw), packHalf2x16(v.g.xy), packHalf2x16(v.g.zw));
    t1 = uvec4(packHalf2x16(v.b.xy), packHalf2x16(v.b.zw), 0u, 0u);
    t2 = uvec4(0u);
}
