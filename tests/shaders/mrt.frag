#version 450
// Two color targets: the vertex color, and a value derived from the uniform block (so both the
// varyings and uniform binding paths are exercised).
layout(location = 0) in vec4 vColor;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outSecond;

layout(binding = 0) uniform Params {
    vec4 tint;
} params;

void main() {
    outColor = vColor;
    outSecond = params.tint * vColor.a;
}
