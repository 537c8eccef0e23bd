// Propagation for RGBA32F volumes. The partial sums travel as the floats' bits in three RGBA32UI
// texels per cell (one per channel), so the kernel has one shape for every format.
#define SH_FORMAT rgba32f
#define PACKED_TEXELS 3
#define PACKED0_FORMAT rgba32ui
#define PACKED1_FORMAT rgba32ui
#define PACKED2_FORMAT rgba32ui
#define INJECT_FORMAT rgba32f // the injection volume (LpvVolumes.cpp)
#include "propagate_body.glsl"

vec4 encodeSh(vec4 v) { return v; }

Sh3 unpackCell(uvec4 t0, uvec4 t1, uvec4 t2) { return Sh3(uintBitsToFloat(t0), uintBitsToFloat(t1), uintBitsToFloat(t2)); }
void packCell(Sh3 v, out uvec4 t0, out uvec4 t1, out uvec4 t2) {
    t0 = floatBitsToUint(v.r);
    t1 = floatBitsToUint(v.g);
    t2 = floatBitsToUint(v.b);
}
