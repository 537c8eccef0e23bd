// Shared by the LPV shaders: SH L1 basis and cosine lobe (gi/ShBasis.h holds the same constants)
// and the volume's placement.
#ifndef LPV_LPV_COMMON_GLSL
#define LPV_LPV_COMMON_GLSL

const float SH_Y0 = 0.282094792;
const float SH_Y1 = 0.488602512;
const float SH_COS_C0 = 0.886226925;
const float SH_COS_C1 = 1.023326708;
const float PI = 3.14159265358979;

vec4 shBasis(vec3 w) { return vec4(SH_Y0, SH_Y1 * w.y, SH_Y1 * w.z, SH_Y1 * w.x); }
vec4 shCosineLobe(vec3 n) { return vec4(SH_COS_C0, SH_COS_C1 * n.y, SH_COS_C1 * n.z, SH_COS_C1 * n.x); }

// RGBA8 volumes store coefficients range-encoded: v in [-range, range] as the code
// 128 + 127 v / range, so zero is a code (gi/ShEncoding.h: the same on the CPU, and why).
vec4 encodeShRange(vec4 v, float range) { return clamp((v / range * 127.0 + 128.0) / 255.0, 0.0, 1.0); }
vec4 decodeShRange(vec4 v, float range) { return (v * 255.0 - 128.0) / 127.0 * range; }
// A cascade's range from gi.rgba8_range, a radiance, and its placement (w: cell size), as
// LpvVolumes::encodeRange.
float cascadeRange(vec4 gridOrigin, float radianceRange) { return radianceRange * gridOrigin.w * gridOrigin.w; }

// Where a vertex shader puts a point it does not draw (a VPL or surfel meant for another slice):
// outside the clip volume in depth as well as on screen, so a rasterizer rejects it before
// clipping. Off screen in x and y only, lavapipe clips points as squares and sends every one
// through its slow clipping path (2-3x the injection and occlusion passes' time).
const vec4 PARKED_POINT = vec4(-4.0, -4.0, 2.0, 1.0);

// m x clip with m's columns read at col .. col + 3, where col is a uniform that is 0. lavapipe
// specializes a shader on uniform values it loads at constant offsets and recompiles it when they
// change: a camera or light matrix read that way recompiled the lookup, the glossy march and the
// VPL clustering on every frame the camera or sun moved. A macro, not a function: a mat4 passed by
// value would be loaded at constant offsets again.
#define MUL_COLUMNS_AT(m, col, clip) \
    ((m)[(col)] * (clip).x + (m)[(col) + 1] * (clip).y + (m)[(col) + 2] * (clip).z + (m)[(col) + 3] * (clip).w)

#endif
