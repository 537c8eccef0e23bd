#version 450
#extension GL_GOOGLE_include_directive : require
// Geometry volume from the camera's view, in the finest cascade: a regular grid of G-buffer
// samples, each marking the cells it passes through as holding a surface of its orientation: per
// axis the largest |n| seen there, not a sum of areas (the camera's samples are as dense as the
// screen makes them, so summing them would make the coverage change whenever the camera moves; the
// coarse cascades' samples add the areas they stand for instead, gv_camera_areas.comp). Catches
// what the light does not see: walls in shadow, surfaces facing away from it. (The albedo multiple
// bounces reflect with is summed at the samples, gv_albedo_sums_body.glsl.)
//
// A sample marks GeometryVolume::kCameraPointsPerSample points: itself; the point half way to its
// right and to its lower neighbour when that lies on its surface more than half a cell away; and
// toward each of its four neighbours that does not lie on its surface, the edge of its footprint.
// Where the samples lie more than a cell apart on a surface (seen at a grazing angle, or far away),
// or a surface ends between two of them, the cells in between were marked or not depending on
// where the samples fell, and the coverage flickered as the camera moved (965 of the Cornell box's
// some 5,000 camera-covered GV cells changed for a third of a cell of camera motion; 216 with these
// points). Most points are not marked: a near surface's samples lie closer than that, and most
// neighbours share one.
//
// A compute pass with integer atomics on packed texels (gv_packed_atomics.glsl): these points were
// drawn into an RGBA8 target with max blending, and a CPU rasterizer shades vertices on one thread:
// they took 8-9 ms of the finest cascade's 11-12 ms occlusion in the benchmark's atrium on llvmpipe.
#include "gv_common.glsl"
#include "gv_packed_atomics.glsl"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = 1) uniform sampler2D gbufferDepth;
layout(binding = 2) uniform sampler2D gbufferNormal;
// Per GV cell, packUnorm4x8 of the largest |n| per axis; w (the top byte) holds the cell's gaps,
// written before (gv_gaps.comp), which a max with 0 keeps.
layout(binding = 3, r32ui) uniform coherent uimage3D cameraMarks;

#include "camera_samples.glsl"

void mark(vec3 p, vec3 n) {
    ivec3 c = surfelCell(p);
    if (!insideVolume(c)) return;
    GV_ATOMIC_MAX_UNORM4X8(cameraMarks, c, vec4(abs(n), 0.0));
}

void main() {
    ivec2 size = textureSize(gbufferDepth, 0);
    int cols = gv.grid.w;
    int rows = max(1, (cols * size.y + size.x / 2) / size.x);
    int sampleNumber = int(gl_GlobalInvocationID.x);
    if (sampleNumber >= cols * rows) return;
    ivec2 index = ivec2(sampleNumber % cols, sampleNumber / cols);
    CameraSample s = cameraSample(index, cols, rows, size);
    if (!s.valid) return;
    mark(s.p, s.n);
    // Half way to the right and the lower neighbour, on its surface and more than half a cell away.
    for (int k = 0; k < 2; ++k) {
        CameraSample q = cameraSample(index + (k == 0 ? ivec2(1, 0) : ivec2(0, 1)), cols, rows, size);
        vec3 d = q.p - s.p;
        if (sameSurface(s, q) && length(d) > 0.5 * gv.gridOrigin.w) mark(s.p + 0.5 * d, s.n);
    }
    // Toward a neighbour on another surface (or none), where the points between samples stop: the
    // edge of the sample's footprint, where the ray through the screen half a sample to that side
    // meets its tangent plane, at most a cell away (a grazing plane would put it far off). Toward a
    // neighbour on its own surface the points above cover the way.
    for (int k = 0; k < 4; ++k) {
        ivec2 side = k == 0 ? ivec2(1, 0) : k == 1 ? ivec2(-1, 0) : k == 2 ? ivec2(0, 1) : ivec2(0, -1);
        if (sameSurface(s, cameraSample(index + side, cols, rows, size))) continue;
        vec2 uv = (vec2(index) + 0.5 + 0.5 * vec2(side)) / vec2(cols, rows);
        vec4 w = gv.invViewProjection * vec4(uv * 2.0 - 1.0, 0.5, 1.0);
        vec3 dir = w.xyz / w.w - gv.camera.xyz;
        float along = dot(dir, s.n);
        if (abs(along) < 1e-6) continue;
        vec3 d = gv.camera.xyz + dir * (dot(s.p - gv.camera.xyz, s.n) / along) - s.p;
        mark(s.p + d * min(1.0, gv.gridOrigin.w / max(length(d), 1e-6)), s.n);
    }
}
