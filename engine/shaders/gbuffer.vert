#version 450
#extension GL_GOOGLE_include_directive : require
// G-buffer geometry: world-space normal and tangent frame, uv.
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inTangent;

#define DRAW_MATERIAL_OUT
#include "draw_uniforms.glsl"
layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex; // multi-drawn

layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec2 vUv;
layout(location = 2) out vec4 vTangent;
layout(location = 3) out vec3 vWorld;

void main() {
    DrawRecord draw = drawRecords.draws[inDrawIndex];
    writeDrawMaterial(draw);
    vec4 world = draw.model * vec4(inPosition, 1.0);
    vNormal = mat3(draw.normalMatrix) * inNormal;
    vTangent = vec4(mat3(draw.model) * inTangent.xyz, inTangent.w);
    vUv = inUv;
    vWorld = world.xyz;
    gl_Position = frame.viewProjection * world;
}
