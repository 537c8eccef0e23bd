#version 450
// Point v lands on the centre of the 16x16 target's pixel list.pixels[v] (y * 16 + x).
layout(binding = 1, std430) readonly buffer List {
    uint pixels[];
} list;

void main() {
    uint i = list.pixels[gl_VertexIndex];
    vec2 pixel = vec2(i % 16u, i / 16u) + 0.5;
    gl_PointSize = 1.0;
    gl_Position = vec4(pixel / 8.0 - 1.0, 0.0, 1.0);
}
