#version 450
// Benchmark baseline only: acc += step, one channel per dispatch.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
layout(binding = 0, std140) uniform Params {
    ivec4 grid;
} params;
layout(binding = 1, rgba16f) uniform readonly image3D step;
layout(binding = 2, rgba16f) uniform image3D acc;

void main() {
    ivec3 cell = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(cell, ivec3(params.grid.x)))) return;
    imageStore(acc, cell, imageLoad(acc, cell) + imageLoad(step, cell));
}
