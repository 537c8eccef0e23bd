#version 450
#extension GL_GOOGLE_include_directive : require
// Benchmark baseline only: the straightforward 5-face gather as a first implementation writes
// it. One channel per dispatch, 4x4x4 groups, face geometry computed per thread (normalize, cross
// products), a generic SH evaluation, image loads that convert the format on every read, and the
// accumulation left to a separate pass (accumulate_baseline.comp). Same mathematics as the
// shipped kernel (gi/shaders/propagate_body.glsl), so the two must agree.
#include "lpv_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0, std140) uniform Params {
    ivec4 grid;  // x: cells per axis
} params;
layout(binding = 1, rgba16f) uniform readonly image3D src;
layout(binding = 2, rgba16f) uniform writeonly image3D dst;

float shEvaluate(vec4 sh, vec3 w) { return dot(sh, shBasis(normalize(w))); }

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    int n = params.grid.x;
    if (any(greaterThanEqual(cell, ivec3(n)))) return;
    vec4 result = vec4(0.0);
    ivec3 offsets[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0), ivec3(0, 0, 1),
                                ivec3(0, 0, -1));
    for (int a = 0; a < 6; ++a) {
        ivec3 nb = cell - offsets[a];
        if (any(lessThan(nb, ivec3(0))) || any(greaterThanEqual(nb, ivec3(n)))) continue;
        vec4 sh = imageLoad(src, nb);
        vec3 d = vec3(offsets[a]);
        // Far face.
        float farSolidAngle = 0.4006696846;
        result += shCosineLobe(d) * (farSolidAngle / PI) * shEvaluate(sh, d);
        // Side faces: the two axes perpendicular to d, both signs.
        vec3 helper = abs(d.x) > 0.5 ? vec3(0, 1, 0) : vec3(1, 0, 0);
        vec3 u = normalize(cross(d, helper));
        vec3 v = normalize(cross(d, u));
        vec3 sides[4] = vec3[4](u, -u, v, -v);
        for (int f = 0; f < 4; ++f) {
            float sideSolidAngle = 0.4234413544;
            vec3 toFace = d + 0.5 * sides[f];
            result += shCosineLobe(sides[f]) * (sideSolidAngle / PI) * shEvaluate(sh, toFace);
        }
    }
    imageStore(dst, cell, result);
}
