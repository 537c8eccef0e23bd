#version 450
// Marks the face a surface crosses between two cell centres along the axis drawn along
// (gi/SurfaceVoxels.h): the lower face of the cell above, at the surface's position rounded.
layout(location = 0) in vec3 vCell;
layout(location = 1) flat in uint vAxis;

layout(binding = 0, std140) uniform Voxelize {
    vec4 gridOrigin; // xyz: corner of cell 0, w: cell size
    uvec4 grid;      // x: cells a side, y: the stamp
} voxelize;
layout(binding = 2, r32ui) uniform writeonly uimage3D faces;

layout(location = 0) out vec4 outUnused; // the pass's target is never read

void main() {
    outUnused = vec4(0.0);
    const int n = int(voxelize.grid.x), axis = int(vAxis);
    ivec3 c = ivec3(floor(vCell));
    c[axis] = int(floor(vCell[axis] + 0.5));
    // A face on the grid's upper boundary is no cell's lower face: beyond the volume is open.
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(n)))) return;
    imageStore(faces, ivec3(3 * c.x + axis, c.y, c.z), uvec4(voxelize.grid.y));
}
