#version 450
// Indexed triangles with a per-vertex color; depth comes from the position's z.
layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec4 inColor;
layout(location = 0) out vec4 vColor;

void main() {
    vColor = inColor;
    gl_Position = vec4(inPosition, 1.0);
}
