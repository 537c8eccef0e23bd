#version 450
#extension GL_GOOGLE_include_directive : require
// Real gaps in the finest cascade's geometry volume: per GV cell and axis, whether the camera sees
// through the cell's slab. The faces pass closes one-cell holes in a wall's coverage
// (gv_faces_body.glsl): the camera's samples miss a wall's cells just behind another object's
// silhouette, and the sun's surfels cover a wall it grazes patchily. But a door 1.5 cells wide has
// one GV cell wholly inside it and the door's edges in its neighbours on both sides, so it was
// closed too and let no light through. Where the depth buffer shows, on the ray through the cell's
// centre, a surface well beyond the cell's slab, the camera saw no wall there: the faces pass then
// leaves that hole open.
//
// Asked once per GV cell here, not at each face corner in the faces pass: a CPU rasterizer runs
// both sides of a branch (it masks lanes), so asking only the corners that closing covers still
// paid for every corner's projections and fetches (with the sun's RSM asked too, the atrium's
// occlusion took 16-24 ms a cascade on llvmpipe so, against 2-5). Asking the sun's RSM here as
// well cost about 1 ms more a frame there, and it is not asked: a gap off screen stays closed.
//
// The answer goes into the top byte of the cell's camera mark (bit `axis`: a gap along that
// axis), which this pass writes whole before the marks pass (gv_camera_marks.comp) adds the
// largest |n| per axis to the other three: this is the marks' clear, and the faces pass fetches
// the mark anyway.
#include "lpv_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform Gaps {
    vec4 gridOrigin; // xyz: LPV cell 0's corner (GV cell 0's centre), w: cell size
    // x: GV cells per axis, y: 0 (the matrices' columns at an index the compiler cannot fold:
    // MUL_COLUMNS_AT)
    ivec4 grid;
    mat4 viewProjection;
    // Column 2 of its inverse (what NDC depth multiplies), at [grid.y] for the same reason.
    vec4 invDepthColumn[1];
} params;
layout(binding = 1) uniform sampler2D cameraDepth;
layout(binding = 3, r32ui) uniform writeonly uimage3D cameraMarks;

void main() {
    ivec3 g = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(g, ivec3(params.grid.x)))) return;
    int col = params.grid.y;
    float cell = params.gridOrigin.w;
    vec3 centre = params.gridOrigin.xyz + vec3(g) * cell;
    // The surface on the ray through the centre: a gap along an axis where it lies beyond the
    // centre and more than 3/4 of a cell from it along that axis. The ray then crossed the whole
    // slab, where the plane of any wall in the cell lies (a surfel snaps to its nearest centre),
    // without meeting a surface. Off screen, or with a nearer surface in front: no. A wall's cell
    // missed at a grazing angle, or behind another object's silhouette, shows the wall itself or
    // that object.
    vec4 clip = MUL_COLUMNS_AT(params.viewProjection, col, vec4(centre, 1.0));
    vec3 ndc = clip.xyz / max(clip.w, 1e-12);
    ivec2 size = textureSize(cameraDepth, 0);
    ivec2 texel = clamp(ivec2((ndc.xy * 0.5 + 0.5) * vec2(size)), ivec2(0), size - 1);
    float d = texelFetch(cameraDepth, texel, 0).r;
    // The hit, unprojected from (ndc.xy, d): what (ndc, 1) unprojects to, (centre, 1) / clip.w,
    // moved along the inverse's depth column (a quarter of the full product's work).
    vec4 h = vec4(centre, 1.0) / clip.w + (d - ndc.z) * params.invDepthColumn[col];
    vec3 hit = h.xyz / h.w;
    bool inView = clip.w > 1e-6 && all(lessThanEqual(abs(ndc), vec3(1.0))) && ndc.z >= 0.0 && d > ndc.z;
    uvec3 gap = uvec3(inView ? greaterThan(abs(hit - centre), vec3(0.75 * cell)) : bvec3(false));
    // The marks' bytes clear: the marks pass adds to them (a per-byte max that leaves the top
    // byte as it is).
    imageStore(cameraMarks, g, uvec4((gap.x | (gap.y << 1) | (gap.z << 2)) << 24, 0u, 0u, 0u));
}
