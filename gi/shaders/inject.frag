#version 450
#extension GL_GOOGLE_include_directive : require
// A VPL as a clamped-cosine lobe of intensity flux / pi, one SH set per colour channel, added to
// the cell by additive blending.
#include "lpv_common.glsl"

layout(location = 0) flat in vec3 vNormal;
layout(location = 1) flat in vec3 vFlux;
layout(location = 0) out vec4 outRed;
layout(location = 1) out vec4 outGreen;
layout(location = 2) out vec4 outBlue;

void main() {
    vec4 lobe = shCosineLobe(vNormal) / PI;
    outRed = lobe * vFlux.r;
    outGreen = lobe * vFlux.g;
    outBlue = lobe * vFlux.b;
}
