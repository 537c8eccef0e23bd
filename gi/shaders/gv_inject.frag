#version 450
// Adds a surfel's projected coverage to its geometry-volume cell (additive blending).
layout(location = 0) flat in vec3 vCoverage;
layout(location = 0) out vec4 outCoverage;

void main() { outCoverage = vec4(vCoverage, 1.0); }
