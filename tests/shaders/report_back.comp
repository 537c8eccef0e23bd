#version 450
// Reports to the CPU through a MemoryAccess::HostRead buffer: how many invocations ran, and the
// largest of a value each computes (as the GI's RGBA8 clipping check does).
layout(local_size_x = 64) in;
layout(binding = 0, std430) buffer Report {
    uint invocations;
    uint peak;
} report;
layout(binding = 1) uniform Params {
    uvec4 scale; // x: each invocation's value is its index times x
} params;

void main() {
    atomicAdd(report.invocations, 1u);
    atomicMax(report.peak, gl_GlobalInvocationID.x * params.scale.x);
}
