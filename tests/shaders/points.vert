#version 450
// Point i lands on the centre of pixel (i % 16, i / 16 % 16) of a 16x16 target, except every third
// one, which is moved outside the clip volume as the GI's injection moves the points of other slices.
void main() {
    int i = gl_VertexIndex;
    vec2 pixel = vec2(i % 16, i / 16 % 16) + 0.5;
    gl_PointSize = 1.0;
    gl_Position = i % 3 == 0 ? vec4(-4.0, -4.0, 0.0, 1.0) : vec4(pixel / 8.0 - 1.0, 0.0, 1.0);
}
