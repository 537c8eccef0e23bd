#version 450
#extension GL_GOOGLE_include_directive : require
// Exposure and a filmic curve (Narkowicz's ACES fit) into the sRGB output target (the target's
// format does the sRGB encode). Debug views other than `indirect` are shown unmapped.
#include "common.glsl"

layout(binding = 1) uniform sampler2D hdrTexture;
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

vec3 aces(vec3 x) { return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

void main() {
    vec3 hdr = textureLod(hdrTexture, vUv, 0.0).rgb;
    int debugView = int(frame.params.w);
    vec3 color = (debugView == 0 || debugView == 6) ? aces(hdr * frame.params.x) : clamp(hdr, 0.0, 1.0);
    outColor = vec4(color, 1.0);
}
