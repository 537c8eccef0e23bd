#version 450
#extension GL_GOOGLE_include_directive : require
// Debug view: one z slice of the accumulated volume, the L0 (average intensity) of each channel.
#include "lpv_common.glsl"

layout(binding = 0, std140) uniform Slice {
    vec4 params;  // x: slice coordinate w (0..1), y: display scale, z: rgba8 range
    ivec4 flags;  // x: encoded
} slice;
layout(binding = 1) uniform sampler3D lpvRed;
layout(binding = 2) uniform sampler3D lpvGreen;
layout(binding = 3) uniform sampler3D lpvBlue;
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

float l0(sampler3D s, vec3 uvw) {
    float v = texture(s, uvw).x;
    return slice.flags.x != 0 ? decodeShRange(vec4(v), slice.params.z).x : v;
}

void main() {
    // Row 0 of the overlay is the top: show +y up.
    vec3 uvw = vec3(vUv.x, 1.0 - vUv.y, slice.params.x);
    vec3 c = vec3(l0(lpvRed, uvw), l0(lpvGreen, uvw), l0(lpvBlue, uvw)) * slice.params.y;
    outColor = vec4(c / (1.0 + c), 1.0);
}
