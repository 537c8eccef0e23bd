#version 450
#extension GL_GOOGLE_include_directive : require
// The cascade classification (gi/CascadeClasses.h): each lookup texel's class as its depth, from
// the rule the lookup and the glossy march share (lpv_cascades.glsl). Sky texels keep the cleared
// depth, which no class draw matches.
#include "cascade_region.glsl"
#include "lpv_common.glsl"

layout(binding = 0, std140) uniform Classify {
    mat4 invViewProjection;
    vec4 gridOrigin[4]; // per cascade: xyz corner of cell 0, w: cell size
    ivec4 grid;         // x: cells per axis, y: cascades, z: glossy march on
    vec4 band;          // x: blend band (fraction of the half-extent)
    ivec4 pixels;       // x: resolution divisor, yz: G-buffer size, w: 0 (MUL_COLUMNS_AT)
} classify;
layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2D normalTexture;

layout(location = 0) in vec2 vUv;

void main() {
    // The texel and its G-buffer pixel as the lookup finds them (lpv_lookup.glsl).
    ivec2 source = min(ivec2(gl_FragCoord.xy) * classify.pixels.x, classify.pixels.yz - 1);
    vec2 uv = (vec2(source) + 0.5) / vec2(classify.pixels.yz);
    float depth = texelFetch(depthTexture, source, 0).r;
    if (depth >= 1.0) {
        gl_FragDepth = 1.0;
        return;
    }
    int col = classify.pixels.w;
    vec4 world = MUL_COLUMNS_AT(classify.invViewProjection, col, vec4(uv * 2.0 - 1.0, depth, 1.0));
    vec3 p = world.xyz / world.w;
    // The finest cascade p is inside of, else the coarsest; in the band when the blend weight
    // (smoothstep of the insideness) is below 1 and a coarser cascade takes the rest.
    int last = classify.grid.y - 1;
    int c = last;
    float inside = 1.0;
    for (int k = last - 1; k >= 0; --k) {
        float i = cascadeInsideness(classify.gridOrigin[k], classify.grid.x, classify.band.x, p);
        if (i > 0.0) {
            c = k;
            inside = i;
        }
    }
    int blend = c < last && inside < 1.0 ? 1 : 0;
    // The glossy march's cascade (lpv_glossy.glsl's rule): the lookup's or the next finer one. It
    // skips fully rough surfaces (the lighting pass weighs it by 1 - roughness).
    vec4 normalRoughness = texelFetch(normalTexture, source, 0);
    vec3 n = normalize(normalRoughness.xyz);
    int glossy = 0;
    if (classify.grid.z != 0 && normalRoughness.w < 1.0)
        glossy = c > 0 && glossyMarchHeld(classify.gridOrigin[c - 1], classify.grid.x, p, n) ? 2 : 1;
    gl_FragDepth = cascadeClassDepth(6 * c + 3 * blend + glossy);
}
