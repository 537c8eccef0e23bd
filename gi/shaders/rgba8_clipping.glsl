// RGBA8 volumes clip light beyond gi.rgba8_range (lpv_common.glsl's encodeShRange). Every shader
// that encodes an RGBA8 result notes here, for its cascade, the largest coefficient it met as a
// multiple of the range, so that the CPU can say so (gi/Rgba8Clipping.h) instead of losing light
// silently. Only coefficients over the range are noted: a volume inside its range costs a max and
// a comparison per encode, no memory traffic. Positive floats order as their bits do, so atomicMax
// on the bits keeps the largest.
#ifndef LPV_RGBA8_CLIPPING_GLSL
#define LPV_RGBA8_CLIPPING_GLSL

#include "lpv_common.glsl"

layout(binding = 23, std430) buffer Rgba8Clipping { // binding: gi::Rgba8Clipping::kBinding
    uint peakBits; // the largest |coefficient| / range over 1, as float bits; 0: none
} rgba8Clipping;

vec4 encodeShNotingClips(vec4 v, float range) {
    const vec4 a = abs(v);
    const float peak = max(max(a.x, a.y), max(a.z, a.w)) / range;
    if (peak > 1.0) atomicMax(rgba8Clipping.peakBits, floatBitsToUint(peak));
    return encodeShRange(v, range);
}

#endif
