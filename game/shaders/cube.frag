#version 450
// Lambert from one directional light plus a constant ambient term.
layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec3 vColor;
layout(location = 0) out vec4 outColor;

layout(binding = 0) uniform Frame {
    mat4 viewProjection;
    mat4 model;
    vec4 lightDirection;
} frame;

void main() {
    float lambert = max(dot(normalize(vNormal), -frame.lightDirection.xyz), 0.0);
    outColor = vec4(vColor * (0.15 + 0.85 * lambert), 1.0);
}
