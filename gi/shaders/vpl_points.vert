#version 450
#extension GL_GOOGLE_include_directive : require
// Debug view: every VPL as a point at its position, coloured by its normalised flux.
#include "lpv_common.glsl"
#include "vpl.glsl"
layout(binding = 0, std140) uniform Points {
    mat4 viewProjection;
} points;
layout(binding = 1, std430) readonly buffer Vpls {
    Vpl vpls[];
};
layout(location = 0) flat out vec3 vColor;

void main() {
    Vpl v = vpls[gl_VertexIndex];
    float m = max(max(v.flux.r, v.flux.g), max(v.flux.b, 1e-8));
    vColor = v.flux.rgb / m;
    gl_PointSize = 1.0;
    gl_Position = v.position.w > 0.0 ? points.viewProjection * vec4(v.position.xyz, 1.0) : PARKED_POINT;
}
