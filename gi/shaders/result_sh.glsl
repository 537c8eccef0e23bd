// A cascade's result volume as a shader that adds to it reads and writes it (the analytic lights,
// the bounce sum): in rgba8 (SH_ENCODED) decoded and encoded in the cascade's range, noting
// clipping (rgba8_clipping.glsl); the float formats as they are.
#ifndef LPV_RESULT_SH_GLSL
#define LPV_RESULT_SH_GLSL

#include "lpv_common.glsl"

#ifdef SH_ENCODED
#include "rgba8_clipping.glsl"
vec4 loadResultSh(vec4 stored, float range) { return decodeShRange(stored, range); }
vec4 storeResultSh(vec4 v, float range) { return encodeShNotingClips(v, range); }
#else
vec4 loadResultSh(vec4 stored, float range) { return stored; }
vec4 storeResultSh(vec4 v, float range) { return v; }
#endif

#endif
