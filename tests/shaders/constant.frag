#version 450
// Writes the pushed color; used with additive blending.
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform Color {
    vec4 value;
} color;

void main() {
    outColor = color.value;
}
