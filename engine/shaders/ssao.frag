#version 450
#extension GL_GOOGLE_include_directive : require
// Screen-space ambient occlusion: 16 hemisphere samples around the normal, in world space,
// compared against the depth buffer. The kernel is fixed and the per-pixel rotation comes from a
// hash of the pixel, so every backend computes the same image.
#include "common.glsl"

layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2D normalTexture;
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outAo;

float hash(vec2 p) { return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453); }

void main() {
    float depth = textureLod(depthTexture, vUv, 0.0).r;
    if (depth >= 1.0 || frame.counts.y == 0) {
        outAo = vec4(1.0);
        return;
    }
    vec3 p = worldFromDepth(vUv, depth);
    // How much the distance to this surface changes within half a pixel. A sample's surface is
    // read at the nearest pixel's centre but placed at the sample's own position, so it can be that
    // far off: where the radius was below a pixel's step (a floor seen at a grazing angle, radius
    // 0.01 m) the floor occluded itself (0.53). Each axis takes the smaller one-sided depth step,
    // so a neighbour across a depth edge (or the sky) does not count; screen derivatives would mix
    // the surfaces of a 2x2 block there. Per pixel, not per sample: per-sample forms of this cost
    // the pass 24-45% on an NVIDIA H100.
    float left = textureLodOffset(depthTexture, vUv, 0.0, ivec2(-1, 0)).r;
    float right = textureLodOffset(depthTexture, vUv, 0.0, ivec2(1, 0)).r;
    float below = textureLodOffset(depthTexture, vUv, 0.0, ivec2(0, -1)).r;
    float above = textureLodOffset(depthTexture, vUv, 0.0, ivec2(0, 1)).r;
    float depthStep =
        0.5 * (min(abs(depth - left), abs(right - depth)) + min(abs(depth - below), abs(above - depth)));
    vec3 q = worldFromDepth(vUv, min(depth + depthStep, 1.0));
    float pixelStep = length(q - frame.cameraPosition.xyz) - length(p - frame.cameraPosition.xyz);
    vec3 n = normalize(textureLod(normalTexture, vUv, 0.0).xyz);
    vec3 helper = abs(n.y) < 0.99 ? vec3(0, 1, 0) : vec3(1, 0, 0);
    float angle = hash(floor(gl_FragCoord.xy)) * 6.2831853;
    vec3 t0 = normalize(cross(helper, n));
    vec3 b0 = cross(n, t0);
    vec3 t = cos(angle) * t0 + sin(angle) * b0;
    vec3 b = cross(n, t);
    float radius = frame.params.y;
    float occlusion = 0.0;
    const int kSamples = 16;
    for (int i = 0; i < kSamples; ++i) {
        // Fibonacci hemisphere directions, scaled so more samples sit near the point.
        float fi = float(i) + 0.5;
        float z = 1.0 - fi / float(kSamples);
        float r = sqrt(max(0.0, 1.0 - z * z));
        float phi = fi * 2.39996323;
        vec3 dir = vec3(r * cos(phi), r * sin(phi), z);
        float scale = mix(0.15, 1.0, (fi / float(kSamples)) * (fi / float(kSamples)));
        vec3 s = p + (t * dir.x + b * dir.y + n * dir.z) * radius * scale;
        vec4 clip = frame.viewProjection * vec4(s, 1.0);
        vec3 ndc = clip.xyz / clip.w;
        vec2 suv = ndc.xy * 0.5 + 0.5;
        if (any(lessThan(suv, vec2(0.0))) || any(greaterThan(suv, vec2(1.0)))) continue;
        float sceneDepth = textureLod(depthTexture, suv, 0.0).r;
        vec3 scenePos = worldFromDepth(suv, sceneDepth);
        float sampleDist = length(s - frame.cameraPosition.xyz);
        float sceneDist = length(scenePos - frame.cameraPosition.xyz);
        // Occluded when the visible surface is in front of the sample, within the radius, by more
        // than a pixel's step.
        float rangeCheck = smoothstep(0.0, 1.0, radius / max(abs(length(scenePos - p)), 1e-4));
        occlusion += (sceneDist < sampleDist - max(0.02 * radius, pixelStep) ? 1.0 : 0.0) * rangeCheck;
    }
    float ao = 1.0 - frame.params.z * occlusion / float(kSamples);
    outAo = vec4(clamp(ao, 0.0, 1.0));
}
