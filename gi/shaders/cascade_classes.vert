#version 450
#extension GL_GOOGLE_include_directive : require
// One cascade class's draw (gi/CascadeClasses.h): the fullscreen triangle at the class's depth, so
// an equal depth test against the classification keeps exactly that class's texels. Vertex
// 3k + i is corner i of class k's triangle (the draw's first vertex names the class).
#include "cascade_region.glsl"

layout(location = 0) out vec2 vUv;

void main() {
    int corner = gl_VertexIndex % 3;
    vec2 p = vec2((corner << 1) & 2, corner & 2);
    vUv = p;
    gl_Position = vec4(p * 2.0 - 1.0, cascadeClassDepth(gl_VertexIndex / 3), 1.0);
}
