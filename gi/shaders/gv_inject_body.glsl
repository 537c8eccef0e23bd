// Adds a surfel to its geometry-volume cell. Light surfels carry their projected area (target 0,
// additive: the RSM samples the surfaces evenly, so areas add up); the finest cascade's camera
// surfels only say "a surface with this orientation passes through here" (target 1, max
// blending): their density follows the screen, so summing their points would make the coverage
// change whenever the camera moves; the max does not. (The coarse cascades' camera samples add
// the areas of their footprints instead, in gv_camera_areas.comp, which accounts for that density.)
layout(location = 0) flat in vec3 vCoverage;
layout(location = 1) flat in int vFromCamera; // 0: the sun's surfel, 1: the camera's, 2: a spot or point light's
layout(location = 2) flat in vec3 vAlbedo;
layout(location = 0) out vec4 outLightCoverage;
layout(location = 1) out vec4 outCameraCoverage;
#ifdef KEEP_ALBEDO
// Albedo sum and surfel count (additive): their ratio is the mean albedo multiple bounces reflect
// with, whichever view saw the surfel. Only with gi.bounces > 1: nothing else reads it, and the
// target would cost the console setup memory it does not have.
layout(location = 2) out vec4 outAlbedo;
#endif

void main() {
    outLightCoverage = vFromCamera != 1 ? vec4(vCoverage, 1.0) : vec4(0.0);
    outCameraCoverage = vFromCamera == 1 ? vec4(vCoverage, 1.0) : vec4(0.0);
#ifdef KEEP_ALBEDO
    outAlbedo = vFromCamera != 2 ? vec4(vAlbedo, 1.0) : vec4(0.0);
#endif
}
