#version 450
// Reads a 3D texture through a sampler and writes to a storage buffer: checks sampled reads of
// what a render pass or compute pass wrote.
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler3D volume;
layout(binding = 1, std430) writeonly buffer Result {
    vec4 values[];
} result;

void main() {
    uint i = gl_GlobalInvocationID.x;
    ivec3 size = textureSize(volume, 0);
    uint count = uint(size.x * size.y * size.z);
    if (i >= count) return;
    ivec3 c = ivec3(i % uint(size.x), (i / uint(size.x)) % uint(size.y), i / uint(size.x * size.y));
    result.values[i] = texelFetch(volume, c, 0);
}
