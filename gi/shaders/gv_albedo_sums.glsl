// The albedo sums' fixed point, shared by the pass that adds them (gv_albedo_sums_body.glsl) and
// the faces pass that reads them (gv_faces_body.glsl).
#ifndef LPV_GV_ALBEDO_SUMS_GLSL
#define LPV_GV_ALBEDO_SUMS_GLSL

// What an albedo of 1 adds up to in a cell of `count` surfels: each adds albedo x units / count
// plus a dither below 1, rounded down, so less than units / count + 1, and the cell's sum stays
// below units + count, which these units keep within a channel's 16 bits. A cell counts at most
// 0x7fff surfels (GeometryVolume.cpp's kMaxAlbedoSurfels), so the units are at least 0x8000.
uint albedoUnits(uint count) { return 0xffffu - count; }

#endif
