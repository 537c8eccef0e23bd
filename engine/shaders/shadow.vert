#version 450
#extension GL_GOOGLE_include_directive : require
// Sun shadow map: depth only.
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
#include "draw_uniforms.glsl"
layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex; // multi-drawn

void main() {
    DrawRecord draw = drawRecords.draws[inDrawIndex];
    gl_Position = frame.sunViewProjection * draw.model * vec4(inPosition, 1.0);
}
