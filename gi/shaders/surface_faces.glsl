// A surface face's word (gi/SurfaceVoxels.h's faces()): the stamp of the pass that marked it
// above the low kFacePlaneBits, in them where the surface crosses the face's column along its
// axis, (offset from the face + 1/2) in 2^kFacePlaneBits-ths of a cell. SurfaceVoxels::kPlaneBits
// is the same width; the tests decode the words with it.
#ifndef SURFACE_FACES_GLSL
#define SURFACE_FACES_GLSL
const uint kFacePlaneBits = 12u;
const uint kFacePlaneMask = (1u << kFacePlaneBits) - 1u;

// The word for a surface `offset` cells (in [-1/2, 1/2)) above its face, marked by pass `stamp`.
uint faceWord(uint stamp, float offset) {
    const float q = floor((offset + 0.5) * float(1u << kFacePlaneBits));
    return (stamp << kFacePlaneBits) | uint(clamp(q, 0.0, float(kFacePlaneMask)));
}

// Whether a segment spanning [span.x, span.y] cells along the face's axis, crossing the face at
// `face` cells from the grid's corner, crosses the surface that marked it in pass `stamp`. A point
// between a surface and the face it rounds to (up to half a cell in front of the surface) is on
// the surface's side: a floor's pixels at the foot of a wall whose face lies in front of the wall
// saw nothing of the room through that face (docs/gi-fidelity.md).
bool surfaceCrossed(uint word, uint stamp, int face, vec2 span) {
    if ((word >> kFacePlaneBits) != stamp) return false;
    const float plane = float(face) + (float(word & kFacePlaneMask) + 0.5) / float(1u << kFacePlaneBits) - 0.5;
    return span.x < plane && plane < span.y;
}
#endif
