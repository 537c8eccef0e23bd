#version 450
// A lit cube: position and normal in object space, transformed by the frame's matrices.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec3 vColor;

layout(binding = 0) uniform Frame {
    mat4 viewProjection;
    mat4 model;
    vec4 lightDirection;
} frame;

void main() {
    vNormal = mat3(frame.model) * inNormal;
    vColor = abs(inNormal) * 0.6 + 0.3;
    gl_Position = frame.viewProjection * frame.model * vec4(inPosition, 1.0);
}
