#version 450
#extension GL_GOOGLE_include_directive : require
// The scene along one axis onto a cascade's cells (gi/SurfaceVoxels.h): each cell column (u, v)
// is k x k pixels (k odd), the middle one on the column's centre line.
layout(location = 0) in vec3 inPosition;

layout(binding = 0, std140) uniform Voxelize {
    vec4 gridOrigin; // xyz: corner of cell 0, w: cell size
    uvec4 grid;      // x: cells a side, y: the stamp, z: pixels a column's side
} voxelize;
#include "draw_uniforms.glsl"
// Multi-drawn: the draw's index, and in bits 30-31 the axis it is drawn along.
layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex;

layout(location = 0) out vec3 vCell; // the position in cells from the grid's corner
layout(location = 1) flat out uint vAxis;

void main() {
    DrawRecord draw = drawRecords.draws[inDrawIndex & 0x3fffffffu];
    const vec3 world = (draw.model * vec4(inPosition, 1.0)).xyz;
    const vec3 g = (world - voxelize.gridOrigin.xyz) / voxelize.gridOrigin.w;
    vCell = g;
    const uint axis = inDrawIndex >> 30;
    vAxis = axis;
    const vec2 uv = axis == 0u ? g.yz : (axis == 1u ? g.zx : g.xy);
    // Depth is unused: the position along the axis travels in vCell, so nothing is clipped by it.
    gl_Position = vec4(uv / float(voxelize.grid.x) * 2.0 - 1.0, 0.5, 1.0);
}
