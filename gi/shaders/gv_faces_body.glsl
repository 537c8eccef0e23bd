// Face transmittance for propagation: for every LPV cell, how much light crosses each of its three
// lower faces (-x, -y, -z), 1 - the mean coverage of the four GV cells at the face's corners along
// the face normal, clamped. The upper faces are the lower faces of the next cells.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform Faces {
    ivec4 grid; // x: LPV cells per axis (the GV has one more)
} params;
layout(binding = 1) uniform sampler3D lightCoverage;
layout(binding = 2, rgba8) uniform writeonly image3D transmittance;
layout(binding = 3) uniform sampler3D cameraCoverage;
#ifdef KEEP_ALBEDO
// Multiple bounces: per GV cell the sum of its surfels' albedos (rgb) and their count (a); per
// LPV cell the mean over its eight corners.
layout(binding = 4) uniform sampler3D albedoSum;
layout(binding = 5, rgba8) uniform writeonly image3D surfelAlbedo;
#endif

// A GV cell's coverage: the light's estimate, or the camera's where that sees more.
vec3 gv(ivec3 c) {
    return max(min(texelFetch(lightCoverage, c, 0).xyz, vec3(1.0)), texelFetch(cameraCoverage, c, 0).xyz);
}

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, ivec3(params.grid.x)))) return;
    // The lower x face spans corners (x, y..y+1, z..z+1); likewise for y and z.
    float bx = (gv(c).x + gv(c + ivec3(0, 1, 0)).x + gv(c + ivec3(0, 0, 1)).x + gv(c + ivec3(0, 1, 1)).x) * 0.25;
    float by = (gv(c).y + gv(c + ivec3(1, 0, 0)).y + gv(c + ivec3(0, 0, 1)).y + gv(c + ivec3(1, 0, 1)).y) * 0.25;
    float bz = (gv(c).z + gv(c + ivec3(1, 0, 0)).z + gv(c + ivec3(0, 1, 0)).z + gv(c + ivec3(1, 1, 0)).z) * 0.25;
    imageStore(transmittance, c, vec4(clamp(vec3(1.0) - vec3(bx, by, bz), 0.0, 1.0), 1.0));
#ifdef KEEP_ALBEDO
    vec4 albedo = vec4(0.0);
    for (int corner = 0; corner < 8; ++corner)
        albedo += texelFetch(albedoSum, c + ivec3(corner & 1, (corner >> 1) & 1, corner >> 2), 0);
    imageStore(surfelAlbedo, c, albedo.a > 0.0 ? vec4(clamp(albedo.rgb / albedo.a, 0.0, 1.0), 1.0) : vec4(0.0));
#endif
}
