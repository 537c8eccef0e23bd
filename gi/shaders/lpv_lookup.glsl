// Indirect irradiance from the accumulated LPV: a trilinear lookup half a cell along the normal,
// the SH intensity integrated against the clamped cosine of the incoming directions, divided by
// the cell's cross-section to turn intensity into radiance. Anisotropic damping: when the field
// grows into the surface (light that arrives from behind it, through the wall), the lookup is
// scaled down by the relative directional derivative along the normal.
//
// Cascades: the finest cascade that holds the point answers; in a band inside its border (a
// quarter of its half-extent, CryEngine's e_GIBlendRatio) it fades into the next coarser one, so
// the irradiance is continuous across cascade borders.
//
// Variants (gi/CMakeLists.txt): CASCADES n chooses per texel among n cascades with branches;
// CASCADE c with BLEND 0 or 1 is one cascade class's draw (gi/CascadeClasses.h): every texel it
// shades belongs to cascade c, inside its band (BLEND 0) or in it (BLEND 1, faded into c + 1).
#include "lpv_cascades.glsl"

layout(binding = 0, std140) uniform Lookup {
    mat4 invViewProjection;
    vec4 gridOrigin[4]; // per cascade: xyz corner of cell 0, w: cell size
    ivec4 grid;         // x: cells per axis, y: volumes are rgba8-encoded, z: damping on
    vec4 encode;        // x: rgba8 range, y: blend band (fraction of the half-extent)
    vec4 intensity;     // x: gi.intensity (already applied at injection), y: damping strength
    ivec4 pixels;       // x: resolution divisor, yz: G-buffer size, w: 0 (see main)
} lookup;
layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2D normalTexture;

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outIrradiance;

// Cascade c's intensity at uvw weighted by `lobe`, per channel (c constant in every call).
vec3 project(int c, vec3 uvw, vec4 lobe) {
    return projectCascade(c, uvw, lobe, lookup.grid.y != 0 ? lookup.encode.x : 0.0);
}

vec3 uvwIn(int c, vec3 p) { return uvwInVolume(lookup.gridOrigin[c], lookup.grid.x, p); }

vec3 irradianceAt(int c, vec3 p, vec3 n) {
    vec3 uvw = uvwIn(c, p);
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return vec3(0.0);
    // Incoming light travels against n: integrate against the lobe around -n.
    vec3 e = project(c, uvw, shCosineLobe(-n));
    float area = lookup.gridOrigin[c].w * lookup.gridOrigin[c].w;
    return max(e, vec3(0.0)) / area;
}

// Cascade c's irradiance at surface point p: half a cell out along n, damped.
vec3 surfaceIrradiance(int c, vec3 p, vec3 n) {
    float cell = lookup.gridOrigin[c].w;
    vec3 front = irradianceAt(c, p + 0.5 * cell * n, n);
    vec3 e = front;
    if (lookup.grid.z != 0) {
        vec3 behind = irradianceAt(c, p - 0.5 * cell * n, n);
        float f = dot(front, vec3(0.2126, 0.7152, 0.0722));
        float bk = dot(behind, vec3(0.2126, 0.7152, 0.0722));
        float growth = max(bk - f, 0.0) / max(bk, 1e-6);
        e *= clamp(1.0 - lookup.intensity.y * growth, 0.0, 1.0);
    }
    return e;
}

float insideness(int c, vec3 p) {
    return cascadeInsideness(lookup.gridOrigin[c], lookup.grid.x, lookup.encode.y, p);
}

// Cascade c's share where p lies in its blend band: 1 inside the band, 0 at its border.
float blendWeight(int c, vec3 p) { return smoothstep(0.0, 1.0, clamp(insideness(c, p), 0.0, 1.0)); }

void main() {
    // This texel answers for G-buffer pixel texel x divisor (gi.resolution; the lighting pass
    // rebuilds the pixels between).
    ivec2 source = min(ivec2(gl_FragCoord.xy) * lookup.pixels.x, lookup.pixels.yz - 1);
    vec2 uv = (vec2(source) + 0.5) / vec2(lookup.pixels.yz);
    float depth = texelFetch(depthTexture, source, 0).r;
    if (depth >= 1.0) {
        outIrradiance = vec4(0.0);
        return;
    }
    vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    // The camera matrix's columns at an index the compiler cannot fold (pixels.w is 0;
    // MUL_COLUMNS_AT): read at constant offsets, it made lavapipe recompile this shader on every
    // frame the camera moved (600-850 ms a frame with a cold shader cache, against 45 ms).
    int col = lookup.pixels.w;
    vec4 world = MUL_COLUMNS_AT(lookup.invViewProjection, col, clip);
    vec3 p = world.xyz / world.w;
    vec3 n = normalize(texelFetch(normalTexture, source, 0).xyz);
#ifdef CASCADE
    // One class's draw: the classification chose the cascade and whether the texel is in its band
    // (the next coarser cascade holds the whole band, so it answers the rest unblended).
    vec3 e = surfaceIrradiance(CASCADE, p, n);
#if BLEND
    float w = blendWeight(CASCADE, p);
    e = w * e;
    e += (1.0 - w) * surfaceIrradiance(CASCADE + 1, p, n);
#endif
#else
    // Finest first, each cascade gets the share of the answer its blend weight gives it of what
    // the finer ones left; a point past a cascade's blend band (weight 1) leaves nothing for the
    // coarser ones, so a pixel looks up one cascade, or two in a band. (Equal to folding from the
    // coarsest in, mix by mix.) CASCADES is compile-time, so each lookup names its own textures:
    // a dynamic cascade index would make a CPU rasterizer run every branch for every pixel.
    vec3 e = vec3(0.0);
    float left = 1.0;
#if CASCADES > 1
    {
        float w = blendWeight(0, p);
        if (w > 0.0) e += w * surfaceIrradiance(0, p, n);
        left = 1.0 - w;
    }
#endif
#if CASCADES > 2
    if (left > 0.0) {
        float w = blendWeight(1, p);
        if (w > 0.0) e += left * w * surfaceIrradiance(1, p, n);
        left *= 1.0 - w;
    }
#endif
#if CASCADES > 3
    if (left > 0.0) {
        float w = blendWeight(2, p);
        if (w > 0.0) e += left * w * surfaceIrradiance(2, p, n);
        left *= 1.0 - w;
    }
#endif
    if (left > 0.0) e += left * surfaceIrradiance(CASCADES - 1, p, n);
#endif
    // The view depth (1 / world.w: clip w is the view depth), for the lighting pass's rebuild.
    outIrradiance = vec4(e, 1.0 / world.w);
}
