// Propagation for RGBA8 volumes (32 bpp per SH texture, as on the consoles), range-encoded. The
// partial sums travel as one RGBA32UI texel per cell: the three channels' 4 x 8-bit codes.
#define SH_FORMAT rgba8
#define SH_ENCODED 1
#define PACKED_TEXELS 1
#define PACKED0_FORMAT rgba32ui
#define INJECT_FORMAT rgba16f // the injection volume (LpvVolumes.cpp)
#include "propagate_body.glsl"

vec4 encodeSh(vec4 v) { return encodeShRange(v, params.encode.x); }
vec4 decodeSh(vec4 v) { return decodeShRange(v, params.encode.x); }

Sh3 unpackCell(uvec4 t0, uvec4 t1, uvec4 t2) {
    return Sh3(decodeSh(unpackUnorm4x8(t0.x)), decodeSh(unpackUnorm4x8(t0.y)), decodeSh(unpackUnorm4x8(t0.z)));
}
void packCell(Sh3 v, out uvec4 t0, out uvec4 t1, out uvec4 t2) {
    t0 = uvec4(packUnorm4x8(encodeSh(v.r)), packUnorm4x8(encodeSh(v.g)), packUnorm4x8(encodeSh(v.b)), 0u);
    t1 = uvec4(0u);
    t2 = uvec4(0u);
}
