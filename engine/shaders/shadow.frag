#version 450
// Depth-only pass; the pipeline has no color target.
void main() {}
