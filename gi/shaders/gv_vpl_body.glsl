// Geometry volume from the light's view: every VPL is also a surfel (the RSM block it clusters),
// drawn into the GV like the radiance injection (gv_common.glsl: one layered draw, or per slice).
// Its area is its share of the block's area across the light (normal.w: a block split at a depth
// edge gives each VPL its texels' share, vpl_cluster.comp) divided by the cosine to the light
// (clamped, so grazing blocks do not explode). The sun's RSM is orthographic: every block has the same area
// across the light. FROM_POINT, a spot's or a point light's (a perspective map): a block subtends
// the axis block's solid angle times cos^3 off the axis, at the VPL's squared distance. (The sun's
// VPLs' albedo, for multiple bounces, is summed by compute: gv_albedo_sums_body.glsl.)
#include "gv_common.glsl"

#include "vpl.glsl"
layout(binding = 1, std430) readonly buffer Vpls {
    Vpl vpls[];
};

layout(location = 0) flat out vec3 vCoverage;

void main() {
    Vpl v = vpls[gl_VertexIndex];
#ifdef FROM_POINT
    vec3 toSurfel = v.position.xyz - gv.lightPosition.xyz;
    float d2 = max(dot(toSurfel, toSurfel), 1e-8);
    vec3 w = toSurfel * inversesqrt(d2);
    float cosAxis = max(dot(w, gv.lightAxis.xyz), 0.0);
    float across = gv.lightPosition.w * v.normal.w * cosAxis * cosAxis * cosAxis * d2;
    float cosLight = max(abs(dot(v.normal.xyz, w)), 0.25);
    vCoverage = surfelCoverage(v.normal.xyz, across / cosLight);
#else
    float cosLight = max(abs(dot(v.normal.xyz, gv.lightDirection.xyz)), 0.25);
    vCoverage = surfelCoverage(v.normal.xyz, gv.lightDirection.w * v.normal.w / cosLight);
#endif
    gl_PointSize = 1.0;
    gl_Position = v.position.w > 0.0 ? surfelPosition(v.position.xyz) : PARKED_POINT;
}
