#version 450
// Each draw of a multi-draw reads the value of its first instance from a per-instance stream.
layout(location = 0) in vec2 inPosition;
layout(location = 6) in uint inValue;
layout(location = 0) flat out uint vValue;

void main() {
    vValue = inValue;
    gl_Position = vec4(inPosition, 0.0, 1.0);
}
