// Propagation for RGBA16F volumes. The partial sums travel as three RGBA16F images (one per
// channel, like the result): llvmpipe converts halves in its image code, where GL's front end
// lowers packHalf2x16/unpackHalf2x16 to integer code.
#define SH_FORMAT rgba16f
#define PARTIALS_AS_SH 1
#define PACKED_TEXELS 3
#define PACKED0_FORMAT rgba16f
#define PACKED1_FORMAT rgba16f
#define PACKED2_FORMAT rgba16f
#define INJECT_FORMAT rgba16f // the injection volume (LpvVolumes.cpp)
#include "propagate_body.glsl"

vec4 encodeSh(vec4 v) { return v; }

Sh3 unpackCell(vec4 t0, vec4 t1, vec4 t2) { return Sh3(t0, t1, t2); }
void packCell(Sh3 v, out vec4 t0, out vec4 t1, out vec4 t2) {
    t0 = v.r;
    t1 = v.g;
    t2 = v.b;
}
