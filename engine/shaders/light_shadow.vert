#version 450
// One view of a spot or point light's shadow map (LightShadows): depth only, seen from the light.
layout(location = 0) in vec3 inPosition;
layout(binding = 1, std140) uniform Draw {
    mat4 model;
    mat4 normalMatrix;
    vec4 baseColor;
    vec4 emissive;
    vec4 material;
} draw;
layout(binding = 2, std140) uniform LightShadowView {
    mat4 viewProjection;
} light;

void main() {
    gl_Position = light.viewProjection * draw.model * vec4(inPosition, 1.0);
}
