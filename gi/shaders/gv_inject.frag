#version 450
// Adds a light's surfel to its geometry-volume cell: its projected area (additive: the RSM
// samples the surfaces evenly, so areas add up). (The finest cascade's camera samples mark their
// cells in a compute pass, gv_camera_marks.comp; the coarse cascades' add the areas of their
// footprints, gv_camera_areas.comp; the albedo multiple bounces reflect with is summed by compute
// too, gv_albedo_sums_body.glsl.)
layout(location = 0) flat in vec3 vCoverage;
layout(location = 0) out vec4 outLightCoverage;

void main() { outLightCoverage = vec4(vCoverage, 1.0); }
