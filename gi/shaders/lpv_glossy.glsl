// Glossy reflections from the LPV (CryEngine 3 talk, "glossy reflections"): march a few cells along
// the reflected view ray and gather the radiance that travels back toward the surface along it.
//
// - The volume stores intensity; light arriving from direction r travels along -r, so each step
//   evaluates the SH in direction -r and divides by the cell's cross-section (as the lookup does).
// - Nearer steps weigh more: their light is the likelier to reach the surface unoccluded (the
//   march ignores occlusion, as the talk's does).
// - Each step evaluates the GGX lobe the lookup evaluates at the surface (glossy_lobes.glsl): per
//   channel of F0 the basis at the lobe's mean light direction, whose length narrows band 1 as
//   roughness widens the lobe; the march runs along that direction (F0's luminance), which leans
//   from the mirror direction toward the normal as roughness grows. Where the march fades out
//   (glossyFade) the two then differ only in where they sample, not in the lobe.
// - Drawn premultiplied over the lookup's glossy radiance (the volume at the lobe's mean light
//   direction, lpv_lookup.glsl): radiance x fade with alpha fade (glossyFade), so the march answers
//   for that share and a surface too rough for it keeps the lookup's reflection.
// - The talk also steps back in propagation time to reduce smearing; with only the accumulated
//   volume kept that is not possible here, so reflections are as blurred as the volume.
// - Compiled once per cascade count (CASCADES, gi/CMakeLists.txt), and every march names its
//   cascade at compile time: with the cascade chosen per pixel at run time, a CPU rasterizer ran
//   every cascade's fetches at every step for every pixel (the atrium's march: 115 ms, 33 ms with
//   one cascade's fetches, on llvmpipe). It still runs every march the shader holds (it runs both
//   sides of a branch), so there the CASCADE c variant marches one cascade in a draw of that
//   cascade's glossy classes (gi/CascadeClasses.h).
#include "lpv_cascades.glsl"
#include "specular_albedo.glsl"
#include "glossy_lobes.glsl"

// GlossyReflections::kSteps. A constant, and a step outside the volume weighs 0 instead of ending
// the loop: the march unrolls into straight code, which llvmpipe ran 15-25% faster than the loop
// with a uniform count and a break (interleaved runs, the benchmark's atrium).
const int GLOSSY_STEPS = 4;

layout(binding = 0, std140) uniform Glossy {
    mat4 invViewProjection;
    vec4 cameraPosition; // xyz
    vec4 gridOrigin[4];  // per cascade: xyz corner of cell 0, w: cell size
    ivec4 grid;          // x: cells per axis, y: volumes are rgba8-encoded, z: cascades (CASCADES), w: 0
    vec4 encode;         // x: gi.rgba8_range (a radiance: cascadeRange), y: gi.glossy_max_roughness
    ivec4 pixels;        // x: resolution divisor, yz: G-buffer size, w: 0 (see main)
} glossy;
layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2D normalTexture;
layout(binding = 15) uniform sampler2D albedoTexture;        // albedo, metallic in alpha
layout(binding = 16) uniform sampler2D specularAlbedoTable; // specular_albedo.glsl

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outRadiance;

// Cascade c's intensity at uvw, each channel through its lobe (c constant in every call).
vec3 project(int c, vec3 uvw, GlossyLobes lobes) {
    float range = glossy.grid.y != 0 ? cascadeRange(glossy.gridOrigin[c], glossy.encode.x) : 0.0;
    return projectCascadePerChannel(c, uvw, lobes.r, lobes.g, lobes.b, range);
}

vec3 uvwIn(int c, vec3 p) { return uvwInVolume(glossy.gridOrigin[c], glossy.grid.x, p); }

bool holds(int c, vec3 p, vec3 n) { return glossyMarchHeld(glossy.gridOrigin[c], glossy.grid.x, p, n); }

// The march through cascade c (constant in every call) along direction r, nearer steps weighing
// more. It starts half a cell out along the normal (like the lookup, so the first step is not
// inside the surface).
vec3 march(int c, vec3 p, vec3 n, vec3 r, GlossyLobes lobes) {
    float cell = glossy.gridOrigin[c].w;
    vec3 start = p + 0.5 * cell * n;
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    for (int step = 1; step <= GLOSSY_STEPS; ++step) {
        vec3 q = start + r * (cell * float(step));
        vec3 uvw = uvwIn(c, q);
        // A step that left the volume weighs nothing (the ray does not come back into a box).
        bool inside = all(greaterThanEqual(uvw, vec3(0.0))) && all(lessThanEqual(uvw, vec3(1.0)));
        float w = inside ? 1.0 / float(step) : 0.0;
        sum += w * max(project(c, uvw, lobes), vec3(0.0));
        weights += w;
    }
    return weights > 0.0 ? sum / (weights * cell * cell) : vec3(0.0);
}

void main() {
    // This texel marches from G-buffer pixel texel x divisor (gi.resolution).
    ivec2 source = min(ivec2(gl_FragCoord.xy) * glossy.pixels.x, glossy.pixels.yz - 1);
    vec2 uv = (vec2(source) + 0.5) / vec2(glossy.pixels.yz);
    float depth = texelFetch(depthTexture, source, 0).r;
    vec4 normalRoughness = texelFetch(normalTexture, source, 0);
    float roughness = clamp(normalRoughness.w, 0.0, 1.0);
    // Sky, and surfaces too rough for a march (glossyFade; most of the Cornell box: the default
    // material is fully rough): the lookup's value stays.
    float fade = glossyFade(roughness, glossy.encode.y);
    if (depth >= 1.0 || fade <= 0.0) {
        outRadiance = vec4(0.0);
        return;
    }
    // Columns at an index the compiler cannot fold (pixels.w is 0; MUL_COLUMNS_AT), as in
    // lpv_lookup.glsl.
    int col = glossy.pixels.w;
    vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    vec4 world = MUL_COLUMNS_AT(glossy.invViewProjection, col, clip);
    vec3 p = world.xyz / world.w;
    vec3 n = normalize(normalRoughness.xyz);
    vec3 v = normalize(glossy.cameraPosition.xyz - p);
    vec4 albedoMetal = texelFetch(albedoTexture, source, 0);
    vec3 f0 = mix(vec3(0.04), albedoMetal.rgb, albedoMetal.a); // as the lighting pass
    GlossyLobes lobes = glossyLobesAt(specularAlbedoTable, n, v, roughness, f0);
    vec3 r = lobes.direction;
    // The finest cascade that holds the march answers for all of it (no blend band: the glossy
    // term is faint next to the diffuse one, and a seam in it is hard to see); the coarsest when
    // none does.
#ifdef CASCADE
    vec3 radiance = march(CASCADE, p, n, r, lobes); // this draw's texels all belong to CASCADE
#else
    vec3 radiance;
    bool marched = false;
#if CASCADES > 1
    if (holds(0, p, n)) {
        radiance = march(0, p, n, r, lobes);
        marched = true;
    }
#endif
#if CASCADES > 2
    if (!marched && holds(1, p, n)) {
        radiance = march(1, p, n, r, lobes);
        marched = true;
    }
#endif
#if CASCADES > 3
    if (!marched && holds(2, p, n)) {
        radiance = march(2, p, n, r, lobes);
        marched = true;
    }
#endif
    if (!marched) radiance = march(CASCADES - 1, p, n, r, lobes);
#endif
    outRadiance = vec4(radiance * fade, fade);
}
