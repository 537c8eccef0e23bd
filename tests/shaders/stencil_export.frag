#version 450
#extension GL_ARB_shader_stencil_export : require
// Stores a stencil per pixel (tests/gpu/RhiScenarios.h, stencilFields): x & 3 in bits 0-1 and
// y & 3 in bits 4-5; columns from kStencilExportColumns on keep the cleared stencil. Adds nothing
// to the colour target (additive blend).
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (p.x >= 12) discard;
    gl_FragStencilRefARB = (p.x & 3) | ((p.y & 3) << 4);
    outColor = vec4(0.0);
}
