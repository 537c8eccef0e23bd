// A coarse cascade's camera coverage (gv_camera_areas.comp): per GV cell g and axis a, texel
// (3 g.x + a, g.y, g.z) of an r32ui volume holds the coverage along a in fixed point, kAreaUnit a
// cell face (integer atomics add in any order to the same sum). 2^20: a cell can sum 4096 faces.
#ifndef LPV_GV_CAMERA_AREAS_GLSL
#define LPV_GV_CAMERA_AREAS_GLSL

const float kAreaUnit = 1048576.0;

#endif
