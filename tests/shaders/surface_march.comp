#version 450
#extension GL_GOOGLE_include_directive : require
// Marches segments between surface points through a cascade's surface faces
// (gi/SurfaceVoxels.h) as the per-pixel gather does (gi/shaders/vpl_visibility.glsl), so a test
// can check which are open.
layout(local_size_x = 1) in;

struct Segment {
    vec4 a;  // xyz: a surface point; w: written, 1 where the segment is open
    vec4 na; // its surface's normal
    vec4 b;  // the other surface point
    vec4 nb; // its surface's normal
};
layout(binding = 0, std140) uniform Grid {
    vec4 origin; // xyz: corner of cell 0, w: cell size
    uvec4 grid;  // x: cells a side, y: the faces' stamp
} params;
layout(binding = 1, std430) buffer Segments { Segment segments[]; };
layout(binding = 2, r32ui) uniform readonly uimage3D faces;

#include "surface_faces.glsl"
bool faceBlocked(ivec3 c, int axis, vec2 span) {
    return surfaceCrossed(imageLoad(faces, ivec3(3 * c.x + axis, c.y, c.z)).x, params.grid.y, c[axis], span);
}
#include "vpl_visibility.glsl"

void main() {
    Segment s = segments[gl_GlobalInvocationID.x];
    segments[gl_GlobalInvocationID.x].a.w =
        surfaceVisibility(params.origin, int(params.grid.x), s.a.xyz, s.na.xyz, s.b.xyz, s.nb.xyz);
}
