#version 450
#extension GL_GOOGLE_include_directive : require
// 4x4 box blur of the AO, matching the 4x4 pattern of the per-pixel rotation.
#include "common.glsl"

layout(binding = 1) uniform sampler2D aoTexture;
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outAo;

void main() {
    vec2 texel = frame.viewport.zw;
    float sum = 0.0;
    for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x) sum += textureLod(aoTexture, vUv + (vec2(x, y) + 0.5) * texel, 0.0).r;
    outAo = vec4(sum / 16.0);
}
