#version 450
// Reads the previous pass's target where this fragment lands and adds the pushed color: checks
// that a render target sampled by the next pass is read after the first pass's writes.
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform Color {
    vec4 value;
} color;
layout(binding = 1) uniform sampler2D previous;

void main() {
    outColor = texelFetch(previous, ivec2(gl_FragCoord.xy), 0) + color.value;
}
