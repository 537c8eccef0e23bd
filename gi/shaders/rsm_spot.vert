#version 450
#extension GL_GOOGLE_include_directive : require
// Reflective shadow map of a spot light: the scene through the perspective frustum around its cone.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(binding = 0, std140) uniform SpotRsm {
    mat4 lightViewProjection;
    vec4 lightPosition;  // xyz; w: 1 / range^2, 0 for an infinite range
    vec4 spotDirection;  // xyz: the cone's axis; w: solid angle of a texel on the axis (sr)
    vec4 cone;           // x: cos(outer), y: cos(inner)
    vec4 intensity;      // rgb: radiant intensity (W/sr)
} rsm;
#include "draw_uniforms.glsl"
layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex; // multi-drawn

layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec2 vUv;
layout(location = 2) out vec3 vWorld;
layout(location = DRAW_INDEX_LOCATION) flat out uint vDrawIndex;

void main() {
    DrawRecord draw = drawRecords.draws[inDrawIndex];
    vDrawIndex = inDrawIndex;
    vec4 world = draw.model * vec4(inPosition, 1.0);
    vNormal = mat3(draw.normalMatrix) * inNormal;
    vUv = inUv;
    vWorld = world.xyz;
    gl_Position = rsm.lightViewProjection * world;
}
