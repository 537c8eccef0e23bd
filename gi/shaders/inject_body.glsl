// Injection: one point per VPL. LAYERED: one draw into every slice, the vertex picks its cell's
// (gl_Layer); otherwise drawn once per volume slice, and VPLs whose cell is in another slice are
// moved outside the clip volume. The cell follows the half-cell shifts along the normal and
// toward the light (gi/LpvReference.cpp does the same on the CPU).
#include "lpv_common.glsl"

#include "vpl.glsl"

layout(binding = 0, std140) uniform Inject {
    vec4 gridOrigin;      // xyz: corner of cell 0; w: cell size
    vec4 lightDirection;  // w 0: xyz is where the light travels; w 1: xyz is the light's position
    vec4 intensity;       // x: gi.intensity
    ivec4 grid;           // x: cells per axis, y: slice being drawn (not LAYERED), z: VPL count
} inject;
layout(binding = 1, std430) readonly buffer Vpls {
    Vpl vpls[];
};

layout(location = 0) flat out vec3 vNormal;
layout(location = 1) flat out vec3 vFlux;

void main() {
    Vpl v = vpls[gl_VertexIndex];
    float cell = inject.gridOrigin.w;
    // A light at a point (a spot light) shines along the line from it to the VPL. A blend, not a
    // branch on the uniform: lavapipe specializes a shader on the uniforms its branches test, and
    // re-specialized this one at every cascade's draw (0.8 ms each). Both terms stay finite, so the
    // blend by 0 or 1 gives one of them exactly.
    vec3 fromLight = v.position.xyz - inject.lightDirection.xyz;
    fromLight *= inversesqrt(max(dot(fromLight, fromLight), 1e-20));
    vec3 travel = mix(inject.lightDirection.xyz, fromLight, step(0.5, inject.lightDirection.w));
    vec3 p = v.position.xyz + 0.5 * cell * (v.normal.xyz - travel);
    ivec3 c = ivec3(floor((p - inject.gridOrigin.xyz) / cell));
    int n = inject.grid.x;
    bool inside = v.position.w > 0.0 && all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(n)));
#ifdef LAYERED
    gl_Layer = clamp(c.z, 0, n - 1);
#else
    inside = inside && c.z == inject.grid.y;
#endif
    vNormal = v.normal.xyz;
    vFlux = v.flux.rgb * inject.intensity.x;
    gl_PointSize = 1.0;
    gl_Position = inside ? vec4((vec2(c.xy) + 0.5) / float(n) * 2.0 - 1.0, 0.0, 1.0) : PARKED_POINT;
}
