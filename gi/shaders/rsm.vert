#version 450
#extension GL_GOOGLE_include_directive : require
// Reflective shadow map: the scene from the sun, fitted to the light volume.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(binding = 0, std140) uniform Rsm {
    mat4 lightViewProjection;
    vec4 lightDirection;  // xyz: where the light travels
    vec4 fluxScale;       // rgb: sun irradiance x texel area (watts per texel at albedo 1)
} rsm;
#include "draw_uniforms.glsl"
layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex; // multi-drawn

layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec2 vUv;
layout(location = DRAW_INDEX_LOCATION) flat out uint vDrawIndex;

void main() {
    DrawRecord draw = drawRecords.draws[inDrawIndex];
    vDrawIndex = inDrawIndex;
    vNormal = mat3(draw.normalMatrix) * inNormal;
    vUv = inUv;
    gl_Position = rsm.lightViewProjection * draw.model * vec4(inPosition, 1.0);
}
