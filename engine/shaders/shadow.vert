#version 450
#extension GL_GOOGLE_include_directive : require
// Sun shadow map: depth only.
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(binding = 1, std140) uniform Draw {
    mat4 model;
    mat4 normalMatrix;
    vec4 baseColor;
    vec4 emissive;
    vec4 material;
} draw;

void main() {
    gl_Position = frame.sunViewProjection * draw.model * vec4(inPosition, 1.0);
}
