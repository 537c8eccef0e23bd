#version 450
// Lists the pixels of a 16x16 target that indirectPointKept (RhiScenarios.h) keeps, and counts them
// into the indirect draw's vertexCount: pixel i = y * 16 + x is kept when i % 5 == 1 or i % 7 == 3.
// Appended with an atomic, so the list's order varies; each pixel appears once.
layout(local_size_x = 64) in;
layout(binding = 0, std430) buffer Args {
    uint unused[4]; // the draw reads its arguments 16 bytes in
    uint vertexCount;
    uint instanceCount;
    uint firstVertex;
    uint firstInstance;
} args;
layout(binding = 1, std430) writeonly buffer List {
    uint pixels[];
} list;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= 256u || (i % 5u != 1u && i % 7u != 3u)) return;
    list.pixels[atomicAdd(args.vertexCount, 1u)] = i;
}
