#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer: albedo (sRGB target) + metallic, world normal + roughness, emissive.
#include "common.glsl"

layout(binding = 1, std140) uniform Draw {
    mat4 model;
    mat4 normalMatrix;
    vec4 baseColor;
    vec4 emissive;
    vec4 material;
} draw;
layout(binding = 2) uniform sampler2D baseColorTexture;
layout(binding = 3) uniform sampler2D normalTexture;

layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec2 vUv;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec3 vWorld;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outEmissive;

void main() {
    vec4 albedo = draw.baseColor;
    if (draw.material.w > 0.5) albedo *= texture(baseColorTexture, vUv);
    vec3 n = normalize(vNormal);
    // Two-sided: thin geometry (cloth) shows its camera-facing side, whatever its winding.
    if (dot(n, frame.cameraPosition.xyz - vWorld) < 0.0) n = -n;
    if (draw.material.z > 0.5) {
        vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
        vec3 b = cross(n, t) * vTangent.w;
        vec3 m = texture(normalTexture, vUv).xyz * 2.0 - 1.0;
        n = normalize(m.x * t + m.y * b + m.z * n);
    }
    outAlbedo = vec4(albedo.rgb, draw.material.x);
    outNormal = vec4(n, draw.material.y);
    outEmissive = vec4(draw.emissive.rgb, 0.0);
}
