#version 450
// The draw's per-instance value as the colour's red.
layout(location = 0) flat in uint vValue;
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(float(vValue), 0.0, 0.0, 1.0); }
