// Geometry volume from the camera's view, in the finest cascade: a regular grid of G-buffer
// samples, each marking its cell as holding a surface of its orientation (gv_inject_body.glsl says
// why not its area; the coarse cascades' samples add their areas, gv_camera_areas.comp). Catches
// what the light does not see: walls in shadow, surfaces facing away from it.
#include "gv_common.glsl"

layout(binding = 1) uniform sampler2D gbufferDepth;
layout(binding = 2) uniform sampler2D gbufferNormal;
layout(binding = 3) uniform sampler2D gbufferAlbedo;

layout(location = 0) flat out vec3 vCoverage;
layout(location = 1) flat out int vFromCamera;
layout(location = 2) flat out vec3 vAlbedo;

#include "camera_samples.glsl"

void main() {
    ivec2 size = textureSize(gbufferDepth, 0);
    int cols = gv.grid.w;
    int rows = max(1, (cols * size.y + size.x / 2) / size.x);
    // Sample s draws GeometryVolume::kCameraPointsPerSample points k: the sample itself
    // (k = 0); the point half way to its right (k = 1) or lower (k = 2) neighbour when that lies on
    // its surface more than half a cell away; and toward each of its four neighbours that does not
    // lie on its surface, the edge of its footprint (k = 3..6). Where the samples lie more than a
    // cell apart on a surface (seen at a grazing angle, or far away), or a surface ends between two
    // of them, the cells in between were marked or not depending on where the samples fell, and the
    // coverage flickered as the camera moved (965 of the Cornell box's some 5,000 camera-covered
    // GV cells changed for a third of a cell of camera motion; 216 with these points). Most points
    // are parked: a near surface's samples lie closer than that, and most neighbours share one
    // (in the benchmark's atrium frame 628 of 28,800 half-way points and 12,599 of 57,600 footprint
    // edges are drawn: normal maps and the arcades' edges make neighbours differ). Tried: listing
    // the drawn points with two compute passes and drawing them indirectly saved 1-3 ms of the
    // atrium's 17-25 on llvmpipe, the drawn edges costing most of what the parked points did.
    //
    // Each kind of point is its own draw and variant (CAMERA_POINTS 0: the samples, 1: the half-way
    // points, 2: the footprint edges), so a vertex runs only its kind's code: a wave of consecutive
    // vertices holding every kind ran all three, and a CPU rasterizer runs every branch anyway.
#if CAMERA_POINTS == 0
    int sampleNumber = gl_VertexIndex, k = 0;
#elif CAMERA_POINTS == 1
    int sampleNumber = gl_VertexIndex / 2, k = 1 + gl_VertexIndex % 2;
#else
    int sampleNumber = gl_VertexIndex / 4, k = 3 + gl_VertexIndex % 4;
#endif
    ivec2 index = ivec2(sampleNumber % cols, sampleNumber / cols);
    CameraSample s = cameraSample(index, cols, rows, size);
    vec3 p = s.p;
    bool valid = s.valid;
#if CAMERA_POINTS == 2
    if (valid) {
        // Toward a neighbour on another surface (or none), where the points between samples stop:
        // the edge of the sample's footprint, where the ray through the screen half a sample to
        // that side meets its tangent plane, at most a cell away (a grazing plane would put it far
        // off). Toward a neighbour on its own surface the points above cover the way.
        ivec2 side = k == 3 ? ivec2(1, 0) : k == 4 ? ivec2(-1, 0) : k == 5 ? ivec2(0, 1) : ivec2(0, -1);
        valid = !sameSurface(s, cameraSample(index + side, cols, rows, size));
        vec2 uv = (vec2(index) + 0.5 + 0.5 * vec2(side)) / vec2(cols, rows);
        vec4 w = gv.invViewProjection * vec4(uv * 2.0 - 1.0, 0.5, 1.0);
        vec3 dir = w.xyz / w.w - gv.camera.xyz;
        float along = dot(dir, s.n);
        if (abs(along) < 1e-6) {
            valid = false;
        } else {
            vec3 d = gv.camera.xyz + dir * (dot(s.p - gv.camera.xyz, s.n) / along) - s.p;
            p = s.p + d * min(1.0, gv.gridOrigin.w / max(length(d), 1e-6));
        }
    }
#elif CAMERA_POINTS == 1
    if (valid) {
        CameraSample q = cameraSample(index + (k == 1 ? ivec2(1, 0) : ivec2(0, 1)), cols, rows, size);
        vec3 d = q.p - s.p;
        valid = sameSurface(s, q) && length(d) > 0.5 * gv.gridOrigin.w;
        p = s.p + 0.5 * d;
    }
#endif
    vCoverage = abs(s.n);
    vFromCamera = 1;
    // What multiple bounces reflect with: the RSM's diffuse reflectance (rsm_diffuse.glsl), none
    // for metals (alpha: metallic), without its Schlick mean (at most 2.8%: the angle light arrives
    // at is not known here).
    vec4 base = texelFetch(gbufferAlbedo, s.pixel, 0);
    vAlbedo = base.rgb * (1.0 - base.a) * (1.0 - mix(vec3(0.04), base.rgb, base.a));
    gl_PointSize = 1.0;
    gl_Position = valid ? surfelPosition(p) : PARKED_POINT;
}
