#version 450
#extension GL_GOOGLE_include_directive : require
// A coarse cascade's camera surfels: each of the camera's samples stands for the piece of its
// surface between it and its neighbours (its footprint), and adds that area, split over the GV
// cells the footprint spans, to the cells' coverage (gv_faces_body.glsl reads it with the light's).
// Where the finest cascade marks a cell as holding a surface of a sample's orientation, a coarse
// cell is large next to a sample: marking it whole made every small object block it, and whether a
// sample landed in a cell changed with every camera move. An area moves smoothly with the camera.
//
// Where a footprint ends matters for the same reason: an edge that jumped a whole sample as the
// camera moved would move the light of the whole cascade. Toward each of its four neighbours a
// footprint reaches:
// - half way, when the neighbour continues its sheet of surface;
// - to the crease, when the neighbour's sheet meets it (a room's corner, a box's edge): where the
//   two tangent planes meet, exactly (half way instead, the cascade test's camera move changed a
//   coarse cascade's irradiance by 2.5% of its peak, against 0.15%);
// - else half way too (a sheet's own edge, against the sky or a drop, or where an occluder hides
//   it). Scanning the pixels for the sheet's last one changed neither the cascade test nor the
//   sealed box, and cost more than the rest of the pass on a CPU rasterizer.
//
// The areas are added with integer atomics in fixed point (kAreaUnit a cell face), so the sum does
// not depend on the order the samples run in, on any backend; a blended float target did the same
// at several times the cost on a CPU rasterizer.
#include "gv_common.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = 1) uniform sampler2D gbufferDepth;
layout(binding = 2) uniform sampler2D gbufferNormal;

#include "camera_samples.glsl"

#include "gv_camera_areas.glsl"
layout(binding = 3, r32ui) uniform uimage3D cameraAreas;

// Whether q continues s's sheet: near its tangent plane, not turned a corner away. Looser than
// sameSurface: a normal map's bumps do not end a wall's area.
bool sameSheet(CameraSample s, CameraSample q) {
    vec3 d = q.p - s.p;
    return q.valid && abs(dot(d, s.n)) <= 0.25 * length(d) + 1e-4 && dot(q.n, s.n) > 0.5;
}

// How far (in uv, along the side's axis) sample s's footprint reaches toward its neighbour at
// `side` (the cases above).
float footprintReach(CameraSample s, vec2 uv, ivec2 index, ivec2 side, int cols, int rows, ivec2 size) {
    int axis = side.x != 0 ? 0 : 1;
    float step = 1.0 / float(axis == 0 ? cols : rows);
    CameraSample q = cameraSample(index + side, cols, rows, size);
    if (sameSheet(s, q)) return 0.5 * step;
    if (q.valid) {
        // The crease: the ray through the way across, dir(t) = da + t (db - da) (directions to
        // points on one plane of constant depth are linear in uv), meets both tangent planes at
        // the same depth where hs dot(dir, nq) = hq dot(dir, ns), linear in t.
        vec2 uvq = (vec2(index + side) + 0.5) / vec2(cols, rows);
        vec4 a4 = gv.invViewProjection * vec4(uv * 2.0 - 1.0, 0.5, 1.0);
        vec4 b4 = gv.invViewProjection * vec4(uvq * 2.0 - 1.0, 0.5, 1.0);
        vec3 da = a4.xyz / a4.w - gv.camera.xyz, db = b4.xyz / b4.w - gv.camera.xyz;
        float hs = dot(s.p - gv.camera.xyz, s.n), hq = dot(q.p - gv.camera.xyz, q.n);
        float f0 = hs * dot(da, q.n) - hq * dot(da, s.n);
        float f1 = hs * dot(db, q.n) - hq * dot(db, s.n);
        float t = f0 / (f0 - f1);
        if (f0 != f1 && t > 0.0 && t < 1.0) {
            vec3 dir = da + t * (db - da);
            vec3 edge = gv.camera.xyz + dir * (hs / dot(dir, s.n));
            // Only a real crease, where the two surfaces meet between the samples: the planes of
            // an occluder's edge and of the wall beyond it meet too, but away from both samples.
            if (length(edge - s.p) + length(edge - q.p) <= 2.0 * length(q.p - s.p)) return t * step;
        }
    }
    return 0.5 * step;
}

void main() {
    ivec2 size = textureSize(gbufferDepth, 0);
    int cols = gv.grid.w;
    int rows = max(1, (cols * size.y + size.x / 2) / size.x); // GeometryVolume::cameraSampleCount
    int sampleNumber = int(gl_GlobalInvocationID.x);
    if (sampleNumber >= cols * rows) return;
    ivec2 index = ivec2(sampleNumber % cols, sampleNumber / cols);
    CameraSample s = cameraSample(index, cols, rows, size);
    if (!s.valid) return;
    // The footprint: where the rays through its edges (e[0] right, e[1] left, e[2] down, e[3] up of
    // the sample) meet its tangent plane, a parallelogram; kept as its bounding box.
    vec2 uv = (vec2(index) + 0.5) / vec2(cols, rows);
    const ivec2 sides[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    vec3 e[4];
    for (int i = 0; i < 4; ++i) {
        vec2 uvs = uv + vec2(sides[i]) * footprintReach(s, uv, index, sides[i], cols, rows, size);
        vec4 w = gv.invViewProjection * vec4(uvs * 2.0 - 1.0, 0.5, 1.0);
        vec3 dir = w.xyz / w.w - gv.camera.xyz;
        float along = dot(dir, s.n);
        float reach = dot(s.p - gv.camera.xyz, s.n) / along;
        // A ray that misses the plane (it turns away from the camera there) reaches nowhere.
        if (abs(along) <= 1e-6 || reach <= 0.0) return;
        e[i] = gv.camera.xyz + dir * reach - s.p;
    }
    vec3 lo = vec3(1e30), hi = vec3(-1e30);
    for (int i = 0; i < 2; ++i)
        for (int j = 2; j < 4; ++j) {
            lo = min(lo, e[i] + e[j]);
            hi = max(hi, e[i] + e[j]);
        }
    // Seen at a grazing angle a sample's footprint grows long and its edges swing as the camera
    // moves; such samples fade out (the light's surfels and the finest cascade cover those walls).
    float area = length(cross(e[0] - e[1], e[2] - e[3])) *
                 smoothstep(0.15, 0.3, abs(dot(normalize(gv.camera.xyz - s.p), s.n)));
    if (area <= 0.0) return;
    // The area, split over the GV cells the box spans across the normal's main axis (snapped along
    // it, as every surfel lands) by the share of the box in each: up to 2 x 2 cells, the box kept to
    // a cell a side, what reaches further cut off with its area (160 samples a row against 32
    // cells: a footprint is rarely that large but at a grazing angle, faded out above).
    vec3 an = abs(s.n);
    int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;
    float cell = gv.gridOrigin.w;
    vec3 q = (s.p + 0.5 * (lo + hi) - gv.gridOrigin.xyz) / cell;
    vec2 halfSize = 0.5 * vec2(hi[u] - lo[u], hi[v] - lo[v]) / cell;
    vec2 kept = min(halfSize, vec2(0.5));
    vec2 boxLo = vec2(q[u], q[v]) - kept, boxHi = vec2(q[u], q[v]) + kept;
    vec2 width = max(2.0 * halfSize, vec2(1e-6));
    vec2 first = floor(boxLo + 0.5); // cell k spans k - 0.5 .. k + 0.5
    vec3 coverage = surfelCoverage(an, area) * kAreaUnit;
    int n = gv.grid.x;
    for (int share = 0; share < 4; ++share) {
        vec2 k = first + vec2(share & 1, share >> 1);
        vec2 overlap = clamp(min(boxHi, k + 0.5) - max(boxLo, k - 0.5), 0.0, 1.0);
        ivec3 g;
        g[axis] = int(floor(q[axis] + 0.5));
        g[u] = int(k.x);
        g[v] = int(k.y);
        if (any(lessThan(g, ivec3(0))) || any(greaterThanEqual(g, ivec3(n)))) continue;
        uvec3 units = uvec3(coverage * (overlap.x * overlap.y / (width.x * width.y)) + 0.5);
        for (int a = 0; a < 3; ++a)
            if (units[a] > 0u) imageAtomicAdd(cameraAreas, ivec3(3 * g.x + a, g.y, g.z), units[a]);
    }
}
