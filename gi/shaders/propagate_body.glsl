// The shipped propagation kernel (included by propagate_<format>.comp, which defines SH_FORMAT).
//
// One thread per destination cell and all three colour channels, in 8x8x1 groups (faster than
// 4x4x4 on this driver, lpv-notes). The 6 x 5 face geometry is compile-time constant: every face's
// evaluation direction has three non-zero basis terms and every re-emission lobe two, so after
// unrolling the compiler folds the zeros and a face costs a 3-term dot, a clamp and a 2-term
// update. Iteration 0 reads the float injection volume and also writes the accumulation as
// injected + propagated, so no separate copy pass is needed.
#include "lpv_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = 0, std140) uniform Propagate {
    ivec4 grid;    // x: cells per axis, y: 1 on the first iteration, z: source is rgba8-encoded
    vec4 encode;   // x: rgba8 range (|coefficient| stored as v * 2 - 1 times range)
} params;
layout(binding = 1) uniform sampler3D srcRed;
layout(binding = 2) uniform sampler3D srcGreen;
layout(binding = 3) uniform sampler3D srcBlue;
layout(binding = 4, SH_FORMAT) uniform writeonly image3D dstRed;
layout(binding = 5, SH_FORMAT) uniform writeonly image3D dstGreen;
layout(binding = 6, SH_FORMAT) uniform writeonly image3D dstBlue;
layout(binding = 7, SH_FORMAT) uniform image3D accRed;
layout(binding = 8, SH_FORMAT) uniform image3D accGreen;
layout(binding = 9, SH_FORMAT) uniform image3D accBlue;

const float FAR_W = 0.4006696846 / PI;   // far-face solid angle / pi
const float SIDE_W = 0.4234413544 / PI;  // side-face solid angle / pi
const float AX = 0.894427191;            // 2 / sqrt(5)
const float LAT = 0.447213595;           // 1 / sqrt(5)

const ivec3 AXES[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0), ivec3(0, 0, 1),
                               ivec3(0, 0, -1));

vec4 decode(vec4 v) { return params.grid.z != 0 ? (v * 2.0 - 1.0) * params.encode.x : v; }
#ifdef SH_ENCODED
vec4 encodeSh(vec4 v) { return clamp(v / params.encode.x * 0.5 + 0.5, 0.0, 1.0); }
vec4 decodeStored(vec4 v) { return (v * 2.0 - 1.0) * params.encode.x; }
#else
vec4 encodeSh(vec4 v) { return v; }
vec4 decodeStored(vec4 v) { return v; }
#endif

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    int n = params.grid.x;
    if (any(greaterThanEqual(cell, ivec3(n)))) return;
    vec4 r = vec4(0.0), g = vec4(0.0), b = vec4(0.0);
    for (int a = 0; a < 6; ++a) {
        ivec3 nb = cell - AXES[a];
        if (any(lessThan(nb, ivec3(0))) || any(greaterThanEqual(nb, ivec3(n)))) continue;
        vec4 sr = decode(texelFetch(srcRed, nb, 0));
        vec4 sg = decode(texelFetch(srcGreen, nb, 0));
        vec4 sb = decode(texelFetch(srcBlue, nb, 0));
        vec3 d = vec3(AXES[a]);
        int axis = a / 2;
        vec3 u = axis == 0 ? vec3(0, 1, 0) : vec3(1, 0, 0);
        vec3 v = axis == 2 ? vec3(0, 1, 0) : vec3(0, 0, 1);
        // Far face: evaluated along d, re-emitted along d.
        vec4 basis = shBasis(d);
        vec4 lobe = shCosineLobe(d) * FAR_W;
        r += lobe * max(0.0, dot(sr, basis));
        g += lobe * max(0.0, dot(sg, basis));
        b += lobe * max(0.0, dot(sb, basis));
        // Side faces: evaluated toward the face centre, re-emitted along the face normal.
        vec3 sides[4] = vec3[4](u, -u, v, -v);
        for (int f = 0; f < 4; ++f) {
            vec4 sbasis = shBasis(AX * d + LAT * sides[f]);
            vec4 slobe = shCosineLobe(sides[f]) * SIDE_W;
            r += slobe * max(0.0, dot(sr, sbasis));
            g += slobe * max(0.0, dot(sg, sbasis));
            b += slobe * max(0.0, dot(sb, sbasis));
        }
    }
    imageStore(dstRed, cell, encodeSh(r));
    imageStore(dstGreen, cell, encodeSh(g));
    imageStore(dstBlue, cell, encodeSh(b));
    vec4 ar, ag, ab;
    if (params.grid.y != 0) {
        // First iteration: the accumulation starts from the injected volume (float, unencoded).
        ar = texelFetch(srcRed, cell, 0);
        ag = texelFetch(srcGreen, cell, 0);
        ab = texelFetch(srcBlue, cell, 0);
    } else {
        ar = decodeStored(imageLoad(accRed, cell));
        ag = decodeStored(imageLoad(accGreen, cell));
        ab = decodeStored(imageLoad(accBlue, cell));
    }
    imageStore(accRed, cell, encodeSh(ar + r));
    imageStore(accGreen, cell, encodeSh(ag + g));
    imageStore(accBlue, cell, encodeSh(ab + b));
}
