// Analytic point and spot lights, added already propagated to the accumulated volume (included by
// point_lights_<format>.comp, which defines SH_FORMAT). The formula and its derivation are in
// gi/include/gi/AnalyticLight.h; gi/src/AnalyticLight.cpp is the same formula on the CPU.
//
// One thread per cell and all three colour channels, in 8x8x1 groups like the propagation. The
// lights are summed in registers, and a cell no light reaches is left untouched (no image traffic).
#include "lpv_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

struct AnalyticLight {
    vec4 positionRange;  // xyz: position; w: range, 0 for infinite
    vec4 intensityCos;   // rgb: radiant intensity x gi.intensity; w: cos(outer cone)
    vec4 spotCos;        // xyz: spot direction; w: cos(inner cone)
};

layout(binding = 0, std140) uniform PointLights {
    vec4 gridOrigin;  // xyz: corner of cell 0; w: cell size
    ivec4 grid;       // x: cells per axis, y: light count
    vec4 encode;      // x: rgba8 range (|coefficient| stored as v * 2 - 1 times range)
} params;
layout(binding = 1, std430) readonly buffer Lights {
    AnalyticLight lights[];
};
layout(binding = 2, SH_FORMAT) uniform image3D accRed;
layout(binding = 3, SH_FORMAT) uniform image3D accGreen;
layout(binding = 4, SH_FORMAT) uniform image3D accBlue;

#ifdef SH_ENCODED
vec4 encodeSh(vec4 v) { return clamp(v / params.encode.x * 0.5 + 0.5, 0.0, 1.0); }
vec4 decodeSh(vec4 v) { return (v * 2.0 - 1.0) * params.encode.x; }
#else
vec4 encodeSh(vec4 v) { return v; }
vec4 decodeSh(vec4 v) { return v; }
#endif

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    int n = params.grid.x;
    if (any(greaterThanEqual(cell, ivec3(n)))) return;
    float s = params.gridOrigin.w;
    vec3 centre = params.gridOrigin.xyz + (vec3(cell) + 0.5) * s;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    bool reached = false;
    for (int i = 0; i < params.grid.y; ++i) {
        AnalyticLight l = lights[i];
        vec3 toCell = centre - l.positionRange.xyz;
        float d2 = dot(toCell, toCell);
        float range = l.positionRange.w;
        if (range > 0.0 && d2 >= range * range) continue;
        // The light's own cell: isotropic there, no direction of arrival (and d -> 0).
        if (ivec3(floor((l.positionRange.xyz - params.gridOrigin.xyz) / s)) == cell) continue;
        vec3 w = toCell * inversesqrt(d2);
        float window = 1.0;
        if (range > 0.0) {
            float q = d2 / (range * range);
            window = clamp(1.0 - q * q, 0.0, 1.0);
        }
        float spot = smoothstep(l.intensityCos.w, l.spotCos.w, dot(w, l.spotCos.xyz));
        // Flux through the cell's cross-section (s^2 / d^2 sr of the light), as a cosine lobe of
        // intensity flux / pi along w.
        vec4 lobe = shCosineLobe(w) * (spot * window * s * s / (d2 * PI));
        r += lobe * l.intensityCos.r;
        g += lobe * l.intensityCos.g;
        b += lobe * l.intensityCos.b;
        reached = true;
    }
    if (!reached) return;
    imageStore(accRed, cell, encodeSh(decodeSh(imageLoad(accRed, cell)) + r));
    imageStore(accGreen, cell, encodeSh(decodeSh(imageLoad(accGreen, cell)) + g));
    imageStore(accBlue, cell, encodeSh(decodeSh(imageLoad(accBlue, cell)) + b));
}
