#version 450
// Profiler overlay: solid rectangles given in pixels (the backdrop, the bars, the labels' glyphs
// and the budget line: ProfilerOverlay::layout), six vertices each.
layout(binding = 0, std140) uniform Overlay {
    vec4 viewport; // width, height
} overlay;
struct Rect {
    vec4 rect;  // x, y, width, height in pixels (row 0 at the top)
    vec4 color;
};
layout(binding = 1, std430) readonly buffer Rects {
    Rect rects[];
};
layout(location = 0) flat out vec4 vColor;

void main() {
    int rect = gl_VertexIndex / 6;
    int corner = gl_VertexIndex % 6;
    vec2 uv = vec2(corner == 1 || corner == 2 || corner == 4 ? 1.0 : 0.0, corner == 2 || corner == 4 || corner == 5 ? 1.0 : 0.0);
    vec4 r = rects[rect].rect;
    vec2 pixel = r.xy + uv * r.zw;
    vColor = rects[rect].color;
    gl_Position = vec4(pixel / overlay.viewport.xy * 2.0 - 1.0, 0.0, 1.0);
}
