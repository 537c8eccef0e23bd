// Face transmittance for propagation: for every LPV cell, how much light crosses each of its three
// lower faces (-x, -y, -z), 1 - the mean coverage of the four GV cells at the face's corners along
// the face normal, clamped. The upper faces are the lower faces of the next cells.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform Faces {
    ivec4 grid; // x: LPV cells per axis (the GV has one more), y: 1 when camera surfels were drawn
} params;
layout(binding = 1) uniform sampler3D lightCoverage;
layout(binding = 2, rgba8) uniform writeonly image3D transmittance;
// The camera's coverage is an r32ui volume a compute pass adds to with atomics, read as an image:
// llvmpipe fetches an integer texture through a sampler several times slower (interleaved runs,
// the atrium's coarse occlusion 2.7-3.0 ms so, against 4.3-5.0 through a usampler3D).
#ifdef CAMERA_AREAS
// A coarse cascade's: the areas the camera's samples saw (gv_camera_areas.comp).
#include "gv_camera_areas.glsl"
layout(binding = 3, r32ui) uniform readonly uimage3D cameraAreas;
#else
// The finest cascade's: the largest |n| of the surfaces its samples saw, packUnorm4x8
// (gv_camera_marks.comp), and in the top byte its real gaps (gv_gaps.comp).
layout(binding = 3, r32ui) uniform readonly uimage3D cameraMarks;
#endif
#ifdef KEEP_ALBEDO
// Multiple bounces: per GV cell its surfels' mean albedo in fixed point and their count
// (gv_albedo_sums_body.glsl); per LPV cell the mean over the surfels at its eight corners.
#include "gv_albedo_sums.glsl"
layout(binding = 4, r32ui) uniform readonly uimage3D albedoSums;
layout(binding = 5, rgba8) uniform writeonly image3D surfelAlbedo;
#endif

// Component `axis` of the light's coverage of GV cell c, at most 1; 0 outside the volume.
float light(ivec3 c, int axis) {
    int n = params.grid.x + 1;
    bool inside = all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(n)));
    return inside ? min(texelFetch(lightCoverage, c, 0)[axis], 1.0) : 0.0;
}

#ifdef CAMERA_AREAS
// Component `axis` of the camera's coverage of GV cell c, at most 1; 0 outside the volume.
float camera(ivec3 c, int axis) {
    int n = params.grid.x + 1;
    bool inside = all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(n)));
    if (!inside) return 0.0;
    return min(float(imageLoad(cameraAreas, ivec3(3 * c.x + axis, c.y, c.z)).r) / kAreaUnit, 1.0);
}
#else
// GV cell c's camera mark: per axis (bytes 0-2) the largest |n| seen there, and in the top byte
// whether the camera sees through it along each axis (bit 24 + axis, gv_gaps.comp);
// 0 outside the volume.
uint mark(ivec3 c) {
    int n = params.grid.x + 1;
    bool inside = all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(n)));
    return inside ? imageLoad(cameraMarks, c).r : 0u;
}
#endif

// The blocking of the lower face along `axis` of LPV cell c: the mean coverage along `axis` of the
// four GV cells at its corners (c + u i + v j, i, j in 0..1; u, v span the face). A corner's
// coverage is the light's estimate, or the camera's where that sees more. Each is closed over
// one-cell holes: a corner whose two neighbours in the face's plane (along u, or along v) both are
// covered counts as covered too (as much as the lesser of them). The camera misses a wall's cells
// where another object's silhouette just hides them, and which ones changes as the camera moves
// (the Cornell box's back wall behind the short box's top): light then leaked through the hole,
// or not, from one frame to the next. The light's surfels cover a wall it grazes patchily (a VPL
// lands in one cell with its whole block's area, stretched by 1 / cos): the Cornell box's back
// wall, lit at cos 0.22 from outside, let a quarter to half of the outside's light through its
// cells in the coarse cascades, unevenly, which the room showed as cell-sized blotches. The
// corners' neighbours overlap: the 12 cells of a 4 x 4 patch of the plane less its corners are
// fetched once for each. In the finest cascade a corner the camera sees through (gv_gaps.comp) is
// a real gap and keeps its own coverage: a door 1.5 cells wide, whose one free cell has the door's
// edges on both sides, was closed before.
float faceBlocking(ivec3 c, int axis, ivec3 u, ivec3 v) {
    float sum = 0.0;
    // seen[i + 1][j + 1], lit[i + 1][j + 1]: the camera's and the light's coverage at c + u i + v j,
    // i, j in -1..2 (corners unused).
    float seen[4][4], lit[4][4];
    // Per corner (i, j in 0..1: bit i + 2 j), whether it is a real gap along `axis` (the finest
    // cascade's marks only).
    uint gaps = 0u;
    for (int i = -1; i <= 2; ++i)
        for (int j = -1; j <= 2; ++j) {
            bool corner = (i == -1 || i == 2) && (j == -1 || j == 2);
            ivec3 at = c + u * i + v * j;
#ifdef CAMERA_AREAS
            // Summed areas leave no holes between samples to close: only the face's own corners.
            bool unused = i < 0 || i > 1 || j < 0 || j > 1;
            seen[i + 1][j + 1] = unused || params.grid.y == 0 ? 0.0 : camera(at, axis);
#else
            bool unused = corner;
            uint m = unused || params.grid.y == 0 ? 0u : mark(at);
            seen[i + 1][j + 1] = unpackUnorm4x8(m)[axis];
            bool own = i >= 0 && i <= 1 && j >= 0 && j <= 1;
            if (own) gaps |= ((m >> (24 + axis)) & 1u) << (i + 2 * j);
#endif
            lit[i + 1][j + 1] = corner ? 0.0 : light(at, axis);
        }
    for (int k = 0; k < 4; ++k) {
        int i = (k & 1) + 1, j = (k >> 1) + 1;
#ifdef CAMERA_AREAS
        float closed = seen[i][j];
#else
        float closed = max(seen[i][j], max(min(seen[i - 1][j], seen[i + 1][j]), min(seen[i][j - 1], seen[i][j + 1])));
#endif
        float l = max(lit[i][j], max(min(lit[i - 1][j], lit[i + 1][j]), min(lit[i][j - 1], lit[i][j + 1])));
        float blocking = max(l, closed);
        // A real gap that closing covered: open again (an empty corner only; the top byte is 0
        // where the camera took no samples).
        if (max(seen[i][j], lit[i][j]) <= 0.0 && ((gaps >> k) & 1u) != 0u) blocking = 0.0;
        sum += blocking;
    }
    return sum * 0.25;
}

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, ivec3(params.grid.x)))) return;
    // The lower x face spans corners (x, y..y+1, z..z+1); likewise for y and z.
    const ivec3 X = ivec3(1, 0, 0), Y = ivec3(0, 1, 0), Z = ivec3(0, 0, 1);
    float bx = faceBlocking(c, 0, Y, Z), by = faceBlocking(c, 1, X, Z), bz = faceBlocking(c, 2, X, Y);
    imageStore(transmittance, c, vec4(clamp(vec3(1.0) - vec3(bx, by, bz), 0.0, 1.0), 1.0));
#ifdef KEEP_ALBEDO
    // Each corner's mean weighed by its count: the mean of all the corners' surfels.
    vec3 albedo = vec3(0.0);
    float surfels = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 g = c + ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
        uint rg = imageLoad(albedoSums, ivec3(2 * g.x, g.y, g.z)).r;
        uint countBlue = imageLoad(albedoSums, ivec3(2 * g.x + 1, g.y, g.z)).r;
        uint count = countBlue & 0xffffu;
        if (count == 0u) continue;
        vec3 sums = vec3(rg & 0xffffu, rg >> 16, countBlue >> 16);
        albedo += sums * (float(count) / float(albedoUnits(count)));
        surfels += float(count);
    }
    imageStore(surfelAlbedo, c, surfels > 0.0 ? vec4(clamp(albedo / surfels, 0.0, 1.0), 1.0) : vec4(0.0));
#endif
}
