#version 450
// Writes a known function of the cell coordinate into a 3D RGBA16F image; the test computes the
// same values on the CPU.
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;
layout(binding = 0, rgba16f) uniform writeonly image3D volume;
layout(binding = 1) uniform Params {
    vec4 scale;
} params;

void main() {
    ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, imageSize(volume)))) return;
    vec3 p = vec3(c) * params.scale.xyz;
    imageStore(volume, c, vec4(sin(p.x) * cos(p.y), p.z * 0.5, float(c.x + 2 * c.y - c.z) / 64.0, 1.0 - p.x * p.y));
}
