#version 450
#extension GL_ARB_shader_viewport_layer_array : require
// Point i lands on texel (i % 4, i / 4 % 4) of slice i / 16 % 4 of a 4^3 layered target, picking
// the slice itself (gl_Layer), except every fifth one, which is moved outside the clip volume.
void main() {
    int i = gl_VertexIndex;
    vec2 pixel = vec2(i % 4, i / 4 % 4) + 0.5;
    gl_PointSize = 1.0;
    gl_Layer = i / 16 % 4;
    gl_Position = i % 5 == 0 ? vec4(-4.0, -4.0, 2.0, 1.0) : vec4(pixel / 2.0 - 1.0, 0.0, 1.0);
}
