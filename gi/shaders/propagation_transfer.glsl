// The transfer of light from a neighbour one cell away along axis e, as one sparse 4x4 matrix
// (derived in gi/PropagationScheme.h from the 5 faces and the published solid angles): with p the
// source at cell - e (light travelling +e) and m the source at cell + e (travelling -e), and a the
// coefficient of e's axis, the cell gains
//   [0] += KA (p0 + m0) + KB (pa - ma),  [a] += KC (p0 - m0) + KD (pa + ma),
//   [other two] += KE (p + m).
// Shared by propagation and the bounce reflection (which needs what a face hands on).
#ifndef LPV_PROPAGATION_TRANSFER_GLSL
#define LPV_PROPAGATION_TRANSFER_GLSL
#include "lpv_common.glsl"

const float FAR_W = 0.4006696846 / PI;  // far-face solid angle / pi
const float SIDE_W = 0.4234413544 / PI; // side-face solid angle / pi
const float AX = 0.894427191;           // 2 / sqrt(5): side-face direction along the axis
const float LAT = 0.447213595;          // 1 / sqrt(5): and across it
const float KA = SH_COS_C0 * SH_Y0 * (FAR_W + 4.0 * SIDE_W);
const float KB = SH_COS_C0 * SH_Y1 * (FAR_W + 4.0 * AX * SIDE_W);
const float KC = SH_COS_C1 * SH_Y0 * FAR_W;
const float KD = SH_COS_C1 * SH_Y1 * FAR_W;
const float KE = 2.0 * SH_COS_C1 * SH_Y1 * LAT * SIDE_W;

#endif
