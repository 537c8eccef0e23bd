#extension GL_ARB_shader_stencil_export : require
// The cascade classification (gi/CascadeClasses.h): each lookup texel's class as its stencil, from
// the rule the lookup and the glossy march share (lpv_cascades.glsl). Sky texels get 0, which no
// class draw matches. Compiled per cascade count (CASCADES, 2 to 4; gi/CMakeLists.txt), so the
// loop over cascades unrolls and reads each cascade's placement at a constant index: with the
// count a uniform, llvmpipe ran the loop with per-lane loads (interleaved runs of the benchmark's
// frames, both scenes, vulkan and gl-egl: median 8.7 -> 7.4 ms, quartiles 7.8-10.7 -> 6.3-8.3).
#include "cascade_region.glsl"
#include "lpv_common.glsl"

layout(binding = 0, std140) uniform Classify {
    mat4 invViewProjection;
    vec4 gridOrigin[4]; // per cascade: xyz corner of cell 0, w: cell size
    ivec4 grid;         // x: cells per axis
    vec4 band;          // x: blend band (fraction of the half-extent), y: glossy max roughness (0: off)
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
        gl_FragStencilRefARB = 0;
        return;
    }
    int col = classify.pixels.w;
    vec4 world = MUL_COLUMNS_AT(classify.invViewProjection, col, vec4(uv * 2.0 - 1.0, depth, 1.0));
    vec3 p = world.xyz / world.w;
    vec4 normalRoughness = texelFetch(normalTexture, source, 0);
    vec3 n = normalize(normalRoughness.xyz);
    // The lookup's cascade: the finest p is inside of, else the coarsest; in the band when the
    // blend weight (smoothstep of the insideness) is below 1 and a coarser cascade takes the rest.
    // The glossy march runs in the lookup's cascade or, where that one holds its start, the next
    // finer one (lpv_glossy.glsl's rule). Finest first, with selects and the cascade index a loop
    // counter: a device that runs both sides of every branch pays for no branch here, and the
    // finer cascade's test needs no array read at a per-texel index.
    const int last = CASCADES - 1;
    int c = last;
    float inside = 1.0;
    bool found = false;
    bool finerHolds = false;   // whether cascade c - 1 holds the march
    bool previousHolds = false; // whether cascade k - 1 does
    for (int k = 0; k < last; ++k) {
        float i = cascadeInsideness(classify.gridOrigin[k], classify.grid.x, classify.band.x, p);
        bool take = !found && i > 0.0;
        c = take ? k : c;
        inside = take ? i : inside;
        finerHolds = take ? previousHolds : finerHolds;
        found = found || i > 0.0;
        previousHolds = glossyMarchHeld(classify.gridOrigin[k], classify.grid.x, p, n);
    }
    if (!found) finerHolds = previousHolds; // c is the coarsest; cascade last - 1 was tested last
    bool blend = c < last && inside < 1.0;
    // The march skips the surfaces it would give nothing (as lpv_glossy.glsl does).
    bool marched = glossyFade(clamp(normalRoughness.w, 0.0, 1.0), classify.band.y) > 0.0;
    gl_FragStencilRefARB = cascadeClassStencil(c, blend, marched, finerHolds ? c - 1 : c);
}
