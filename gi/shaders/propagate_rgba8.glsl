// Propagation for RGBA8 volumes (32 bpp per SH texture, as on the consoles), range-encoded. The
// partial sums travel as one RGBA32UI texel per cell: the 12 coefficients as 10-bit codes, three
// to a word (zero at code 512, as lpv_common.glsl's 8-bit codes have it at 128). The texel has the
// room, and each iteration rounds the sums again. Against RGBA16F volumes at the default
// gi.rgba8_range (12), the indirect light's mean difference per pixel with 8-bit sums was 6.0% of
// the mean (Cornell box) and 7.2% (atrium), with 10-bit ones 5.4% and 6.1%; the means themselves
// within about 1% either way. The result volumes stay 8-bit (encodeSh).
#define SH_FORMAT rgba8
#define SH_ENCODED 1
#define PACKED_TEXELS 1
#define PACKED0_FORMAT rgba32ui
#define INJECT_FORMAT rgba16f // the injection volume (LpvVolumes.cpp)
#include "propagate_body.glsl"
#ifdef TO_RESULT
#include "rgba8_clipping.glsl"
vec4 encodeSh(vec4 v) { return encodeShNotingClips(v, params.encode.x); }
#else
vec4 encodeSh(vec4 v) { return encodeShRange(v, params.encode.x); } // not called: no result here
#endif

uint pack3(vec3 v) {
    uvec3 q = uvec3(round(clamp(v / params.encode.x * 511.0 + 512.0, 0.0, 1023.0)));
    return q.x | (q.y << 10) | (q.z << 20);
}
vec3 unpack3(uint w) {
    vec3 q = vec3(uvec3(w, w >> 10, w >> 20) & 1023u);
    return (q - 512.0) / 511.0 * params.encode.x;
}
Sh3 unpackCell(uvec4 t0, uvec4 t1, uvec4 t2) {
    vec3 a = unpack3(t0.x), b = unpack3(t0.y), c = unpack3(t0.z), d = unpack3(t0.w);
    return Sh3(vec4(a, b.x), vec4(b.yz, c.xy), vec4(c.z, d));
}
void packCell(Sh3 v, out uvec4 t0, out uvec4 t1, out uvec4 t2) {
    t0 = uvec4(pack3(v.r.xyz), pack3(vec3(v.r.w, v.g.xy)), pack3(vec3(v.g.zw, v.b.x)), pack3(v.b.yzw));
    t1 = uvec4(0u);
    t2 = uvec4(0u);
}
