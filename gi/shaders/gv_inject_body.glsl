// Adds a surfel to its geometry-volume cell: the light's surfels their projected area (target 0,
// additive: the RSM samples the surfaces evenly, so areas add up). (The finest cascade's camera
// samples mark their cells in a compute pass, gv_camera_marks.comp; the coarse cascades' add the
// areas of their footprints, gv_camera_areas.comp.)
layout(location = 0) flat in vec3 vCoverage;
// 0: the sun's surfel, 1: the camera's sample (albedo only), 2: a spot or point light's (coverage only)
layout(location = 1) flat in int vFromCamera;
layout(location = 2) flat in vec3 vAlbedo;
layout(location = 0) out vec4 outLightCoverage;
#ifdef KEEP_ALBEDO
// Albedo sum and surfel count (additive): their ratio is the mean albedo multiple bounces reflect
// with, whichever view saw the surfel. Only with gi.bounces > 1: nothing else reads it, and the
// target would cost the console setup memory it does not have.
layout(location = 1) out vec4 outAlbedo;
#endif

void main() {
    outLightCoverage = vFromCamera != 1 ? vec4(vCoverage, 1.0) : vec4(0.0);
#ifdef KEEP_ALBEDO
    outAlbedo = vFromCamera != 2 ? vec4(vAlbedo, 1.0) : vec4(0.0);
#endif
}
