// Shared by the geometry-volume shaders: the volume's placement and how a surfel is stored.
//
// The geometry volume (GV) holds, per cell, how much surface it contains as seen along each axis:
// from the light's surfels (sum of area x |n.x|, |n.y|, |n.z|) / cell area, and from the
// camera's, the largest |n| of a surface seen there (the finest cascade) or the sum of the areas
// its samples stand for (the coarse ones, gv_camera_areas.comp). Its cells are centred on the LPV's cell corners
// (offset half a cell), so the four around a face of an LPV cell say how much of that face is
// covered. We keep this projected coverage instead of the papers' SH L1 blocking lobe because
// propagation only ever asks along an axis, and an L1 lobe cannot hold a two-sided surface: the
// two faces of a thin wall, one seen by the light and one by the camera, would cancel.
#ifndef LPV_GV_COMMON_GLSL
#define LPV_GV_COMMON_GLSL

#include "lpv_common.glsl"

layout(binding = 0, std140) uniform GeometryInject {
    vec4 gridOrigin;   // xyz: corner of LPV cell 0 (= centre of GV cell 0); w: cell size
    vec4 lightDirection; // xyz: where the light travels; w: RSM area per VPL (m^2, across the light);
                         // FROM_POINT's albedo sums: xy the cone's smoothstep edges
    mat4 invViewProjection; // camera surfels: clip -> world
    vec4 camera;       // xyz: camera position
    ivec4 grid;        // x: GV cells per axis, y: slice being drawn (not LAYERED), z: VPL count, w: samples per row
    vec4 whiteTexelFlux; // rgb: the flux an RSM texel of albedo 1 reflects
    // FROM_POINT (the surfels of a spot or point light's RSM): xyz the light's position, w the solid
    // angle of a VPL's texel block on the RSM's axis (sr); and the axis, w 1 / range^2 (0: none).
    // Its albedo sums take the light's radiant intensity as whiteTexelFlux.
    vec4 lightPosition;
    vec4 lightAxis;
    // The albedo sums (gv_albedo_sums_body.glsl): y the stride between the surfels taken (more
    // than 1 only where a cell could count too many), z the camera samples before the VPLs.
    ivec4 albedoSums;
} gv;

// The GV cell a surfel at p lands in: the one whose centre (an LPV corner) is nearest.
ivec3 surfelCell(vec3 p) { return ivec3(floor((p - gv.gridOrigin.xyz) / gv.gridOrigin.w + 0.5)); }

bool insideVolume(ivec3 c) {
    return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(gv.grid.x)));
}

// Where a surfel drawn as a point lands: its cell (surfelCell) as a point position and (LAYERED)
// the slice it picks; without LAYERED, only if it is in the slice being drawn. Else a position
// outside the clip volume.
vec4 surfelPosition(vec3 p) {
    ivec3 c = surfelCell(p);
    int n = gv.grid.x;
    bool inside = insideVolume(c);
#ifdef LAYERED
    gl_Layer = clamp(c.z, 0, n - 1);
#else
    inside = inside && c.z == gv.grid.y;
#endif
    return inside ? vec4((vec2(c.xy) + 0.5) / float(n) * 2.0 - 1.0, 0.0, 1.0) : PARKED_POINT;
}

// A surfel's projected coverage along the axes, in units of one cell face.
vec3 surfelCoverage(vec3 normal, float area) {
    return abs(normal) * area / (gv.gridOrigin.w * gv.gridOrigin.w);
}

#endif
