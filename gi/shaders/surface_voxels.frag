#version 450
#extension GL_GOOGLE_include_directive : require
// Marks the face a surface crosses between two cell centres along the axis drawn along
// (gi/SurfaceVoxels.h): the lower face of the cell above, at the surface's position rounded, with
// where the surface lies off it (surface_faces.glsl); of surfaces crossing one face, the highest.
// Each cell column is k x k pixels (k = grid.z, odd): the middle one, on the column's centre
// line, marks the face; every one adds 1 to the face's area, in k^2ths of a face.
#include "surface_areas.glsl"
#include "surface_faces.glsl"

layout(location = 0) in vec3 vCell;
layout(location = 1) flat in uint vAxis;

layout(binding = 0, std140) uniform Voxelize {
    vec4 gridOrigin; // xyz: corner of cell 0, w: cell size
    uvec4 grid;      // x: cells a side, y: the stamp, z: pixels a column's side
} voxelize;
layout(binding = 2, r32ui) uniform uimage3D faces;
// The stamp above the low kAreaCountBits, the samples in them (SurfaceVoxels::areas()).
layout(binding = 3, r32ui) uniform uimage3D areas;

layout(location = 0) out vec4 outUnused; // the pass's target is never read

// Room left under the count's top for the fragments that add while one reads it.
const uint kMostSamples = (1u << kAreaCountBits) - 256u;

void main() {
    outUnused = vec4(0.0);
    const int n = int(voxelize.grid.x), axis = int(vAxis), k = int(voxelize.grid.z);
    ivec3 c = ivec3(floor(vCell));
    c[axis] = int(floor(vCell[axis] + 0.5));
    // A face on the grid's upper boundary is no cell's lower face: beyond the volume is open.
    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(n)))) return;
    const ivec3 texel = ivec3(3 * c.x + axis, c.y, c.z);
    // Pixel k i + k / 2 is column i's middle (a flipped y keeps it so: k n - 1 - (k i + k / 2)).
    const ivec2 within = ivec2(gl_FragCoord.xy) % k;
    // The highest, not the last: the same word on every backend and every run.
    if (all(equal(within, ivec2(k / 2))))
        imageAtomicMax(faces, texel, faceWord(voxelize.grid.y, vCell[axis] - float(c[axis])));
    // A face last counted by an earlier pass starts from 0 (its stamp is lower): the first of
    // this pass's samples to get there raises it to this stamp with no count, and every sample
    // adds after its own raise. No clear, and so no barrier, before the pass.
    const uint stamped = voxelize.grid.y << kAreaCountBits;
    const uint before = max(imageAtomicMax(areas, texel, stamped), stamped);
    if ((before & kAreaCountMask) < kMostSamples) imageAtomicAdd(areas, texel, 1u);
}
