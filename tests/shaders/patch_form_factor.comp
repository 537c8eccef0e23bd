#version 450
#extension GL_GOOGLE_include_directive : require
// Evaluates the gather's patch form factor (gi/shaders/patch_form_factor.glsl) for each case, so a
// test can compare it with the integral over the rectangle.
#include "patch_form_factor.glsl"

layout(local_size_x = 1) in;

struct Case {
    vec4 receiver; // xyz: the point, w: the rectangle's half extent along its tangent
    vec4 normal;   // xyz: the receiver's normal, w: its half extent along its bitangent
    vec4 centre;   // xyz: the rectangle's centre
    vec4 facing;   // xyz: the rectangle's normal
    vec4 result;   // x: the form factor; y, z: the packed extents read back
};
layout(binding = 0, std430) buffer Cases { Case cases[]; };

void main() {
    Case c = cases[gl_GlobalInvocationID.x];
    vec2 e = patchExtents(packPatchExtents(vec2(c.receiver.w, c.normal.w)));
    cases[gl_GlobalInvocationID.x].result =
        vec4(patchFormFactor(c.receiver.xyz, c.normal.xyz, c.centre.xyz, c.facing.xyz, vec2(c.receiver.w, c.normal.w)),
             e, 0.0);
}
