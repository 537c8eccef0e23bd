#version 450
#extension GL_GOOGLE_include_directive : require
// One view of a spot or point light's shadow map (LightShadows): depth only, seen from the light.
layout(location = 0) in vec3 inPosition;
#include "draw_uniforms.glsl"
layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex; // multi-drawn
layout(binding = 2, std140) uniform LightShadowView {
    mat4 viewProjection;
} light;

void main() {
    DrawRecord draw = drawRecords.draws[inDrawIndex];
    gl_Position = light.viewProjection * draw.model * vec4(inPosition, 1.0);
}
