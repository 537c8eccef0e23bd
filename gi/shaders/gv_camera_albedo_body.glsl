// The finest cascade's camera samples' albedo, for multiple bounces (gi.bounces > 1): each valid
// sample draws one point into its GV cell, adding its albedo and a count of 1 to the albedo sums
// (gv_inject_body.glsl); the faces pass turns them into each LPV cell's mean. The coverage the
// samples mark (up to 7 points each) is a compute pass, gv_camera_marks.comp; the albedo stays a
// draw because additive blending sums the half floats in the order the points were submitted,
// which keeps the volumes the same from run to run, where atomics on floats would not, and a 32-bit
// integer sum per channel and count would take 16 bytes a cell, more than the console preset's 3 MiB
// has room for. Only the samples themselves add: a cell marked only by the points between samples
// takes its LPV cells' albedo from their other corners.
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
    CameraSample s = cameraSample(ivec2(gl_VertexIndex % cols, gl_VertexIndex / cols), cols, rows, size);
    vCoverage = vec3(0.0);
    vFromCamera = 1;
    // What multiple bounces reflect with: the RSM's diffuse reflectance (rsm_diffuse.glsl), none
    // for metals (alpha: metallic), without its Schlick mean (at most 2.8%: the angle light arrives
    // at is not known here).
    vec4 base = texelFetch(gbufferAlbedo, s.pixel, 0);
    vAlbedo = base.rgb * (1.0 - base.a) * (1.0 - mix(vec3(0.04), base.rgb, base.a));
    gl_PointSize = 1.0;
    gl_Position = s.valid ? surfelPosition(s.p) : PARKED_POINT;
}
