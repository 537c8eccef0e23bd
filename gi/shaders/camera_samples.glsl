// The camera's G-buffer samples that fill the geometry volume (gv_camera_marks.comp,
// gv_camera_areas.comp): a regular grid of cols x rows over the depth buffer. Needs
// gv_common.glsl's uniforms and gbufferDepth, gbufferNormal declared first.
#ifndef LPV_CAMERA_SAMPLES_GLSL
#define LPV_CAMERA_SAMPLES_GLSL

// Sample (column, row) of the grid: its G-buffer pixel, depth, world position and normal.
struct CameraSample {
    bool valid;
    vec3 p;
    vec3 n;
    ivec2 pixel;
};

CameraSample cameraSample(ivec2 index, int cols, int rows, ivec2 size) {
    CameraSample s;
    vec2 uv = (vec2(index) + 0.5) / vec2(cols, rows);
    s.pixel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
    float depth = texelFetch(gbufferDepth, s.pixel, 0).r;
    s.n = texelFetch(gbufferNormal, s.pixel, 0).xyz;
    // Clip space has y pointing down the image and depth 0..1 (engine/render/CameraMatrices.h).
    vec4 world = gv.invViewProjection * vec4(uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0, depth, 1.0);
    s.p = world.xyz / world.w;
    s.valid = all(greaterThanEqual(index, ivec2(0))) && all(lessThan(index, ivec2(cols, rows))) && depth < 1.0 &&
              dot(s.n, s.n) > 0.25;
    s.n = normalize(s.n);
    return s;
}

// Whether neighbour q lies on sample s's surface: near its tangent plane and facing alike.
bool sameSurface(CameraSample s, CameraSample q) {
    vec3 d = q.p - s.p;
    return q.valid && abs(dot(d, s.n)) <= 0.1 * length(d) + 1e-4 && dot(q.n, s.n) > 0.9;
}

#endif
