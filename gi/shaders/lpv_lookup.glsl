// Indirect irradiance from the accumulated LPV: a trilinear lookup half a cell along the normal,
// the SH intensity integrated against the clamped cosine of the incoming directions, divided by
// the cell's cross-section to turn intensity into radiance. Anisotropic damping: when the field
// grows into the surface (light that arrives from behind it, through the wall), the lookup is
// scaled down by the relative directional derivative along the normal.
//
// The same fetches give the glossy radiance where the march (lpv_glossy.glsl) does not run or
// fades out: the volume's radiance averaged over the GGX lobe seen from the camera. Radiance in an
// L1 volume is linear in the direction, so that average is the field evaluated at the lobe's mean
// light direction (glossy_lobes.glsl, per channel of F0), exactly, at the surface point; the
// march, where it runs, evaluates the same lobes a few cells out along the mean direction instead
// and is drawn over it. With gi.glossy off, the cosine lobe's E / pi, which costs nothing.
//
// Cascades: the finest cascade that holds the point answers; in a band inside its border (a
// quarter of its half-extent, CryEngine's e_GIBlendRatio) it fades into the next coarser one, so
// the irradiance is continuous across cascade borders.
//
// Variants (gi/CMakeLists.txt): CASCADES n chooses per texel among n cascades with branches;
// CASCADE c with BLEND 0 or 1 is one cascade class's draw (gi/CascadeClasses.h): every texel it
// shades belongs to cascade c, inside its band (BLEND 0) or in it (BLEND 1, faded into c + 1).
//
// Thin walls: with gi.occlusion a cascade's filter does not read across the faces its geometry
// volume blocks (keptInside).
#include "lpv_cascades.glsl"
#include "rebuild_normal.glsl"
#include "specular_albedo.glsl"
#include "glossy_lobes.glsl"

layout(binding = 0, std140) uniform Lookup {
    mat4 invViewProjection;
    vec4 gridOrigin[4]; // per cascade: xyz corner of cell 0, w: cell size
    ivec4 grid;         // x: cells per axis, y: volumes are rgba8-encoded, z: damping on
    vec4 encode;        // x: gi.rgba8_range (a radiance: cascadeRange), y: blend band (fraction
                        // of the half-extent), z, bit c: cascade c's faceTransmittance is bound
                        // and built (gi.occlusion)
    vec4 intensity;     // x: gi.intensity (already applied at injection), y: damping strength,
                        // z: 1 the glossy lobe's mean direction, 0 the cosine lobe (gi.glossy off)
    ivec4 pixels;       // x: resolution divisor, yz: G-buffer size, w: 0 (see main)
    vec4 cameraPosition; // xyz
} lookup;
layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2D normalTexture;
layout(binding = 15) uniform sampler2D albedoTexture;        // albedo, metallic in alpha
layout(binding = 16) uniform sampler2D specularAlbedoTable; // specular_albedo.glsl

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outIrradiance;
layout(location = 1) out vec4 outGlossy;

vec3 uvwIn(int c, vec3 p) { return uvwInVolume(lookup.gridOrigin[c], lookup.grid.x, p); }

// Cascade c's rgba8 range, or 0 for float volumes.
float encodeRangeOf(int c) { return lookup.grid.y != 0 ? cascadeRange(lookup.gridOrigin[c], lookup.encode.x) : 0.0; }

// Cascade c's irradiance and glossy radiance at point p (c constant in every call); 0 outside it.
CascadeSample lightAt(int c, vec3 p, LookupLobes lobes) {
    vec3 uvw = uvwIn(c, p);
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return CascadeSample(vec3(0.0), vec3(0.0));
    CascadeSample s = sampleCascade(c, uvw, lobes, encodeRangeOf(c));
    // Intensity over the cell's cross-section is radiance.
    float area = lookup.gridOrigin[c].w * lookup.gridOrigin[c].w;
    return CascadeSample(max(s.irradiance, vec3(0.0)) / area, max(s.glossy, vec3(0.0)) / area);
}

// Each cascade's face transmittance (GeometryVolume). Bindings without one of their own (a cascade
// that does not exist, or all but the finest's without gi.lookup_occlusion) hold another's, unread.
layout(binding = 17) uniform sampler3D faceTransmittance0;
layout(binding = 18) uniform sampler3D faceTransmittance1;
layout(binding = 19) uniform sampler3D faceTransmittance2;
layout(binding = 20) uniform sampler3D faceTransmittance3;

// Cascade c's (a constant in every call) face transmittances of cell `cell`.
vec3 facesAt(int c, ivec3 cell) {
    if (c == 0) return texelFetch(faceTransmittance0, cell, 0).xyz;
    if (c == 1) return texelFetch(faceTransmittance1, cell, 0).xyz;
    if (c == 2) return texelFetch(faceTransmittance2, cell, 0).xyz;
    return texelFetch(faceTransmittance3, cell, 0).xyz;
}

// Where to sample cascade c for point q (half a cell out from surface point p) so that its
// trilinear filter does not read across the faces the geometry volume blocks. A wall thinner than
// a cell stands between two cell centres, and the cell beyond it holds the light of the wall's far
// side (injected half a cell out from that side): a plain lookup on the near side mixed it in
// (measured in tests/gi/ThinWallLookupGpuTests.cpp). Per axis, the filter's share of the neighbour
// across from the cell q lies in is scaled by the transmittance of the face between them, and the hardware
// filter then fetches at the point those shares give: 3 more point fetches, not 8 per volume, and
// one lookup, not a lookup per branch on a CPU rasterizer. A diagonal neighbour is cut by the faces
// on the home cell's row and column only (the path through the other corner is not looked at).
vec3 keptInside(int c, vec3 q, vec3 p) {
    vec4 origin = lookup.gridOrigin[c];
    int n = lookup.grid.x;
    // Cell coordinates: cell centres at whole numbers.
    vec3 t = (q - origin.xyz) / origin.w - 0.5;
    vec3 pt = (p - origin.xyz) / origin.w - 0.5;
    vec3 camera = (lookup.cameraPosition.xyz - origin.xyz) / origin.w - 0.5;
    vec3 base = floor(t);
    vec3 f = t - base;
    ivec3 home = ivec3(base) + ivec3(greaterThanEqual(f, vec3(0.5)));
    for (int a = 0; a < 3; ++a) {
        // The face between home and the other cell of the filter along a: home's lower face when
        // that cell is below it, else the upper cell's lower face.
        ivec3 upper = home;
        if (f[a] < 0.5) upper[a] += 1;
        float open = facesAt(c, clamp(upper, ivec3(0), ivec3(n - 1)))[a];
        // Which side of that face to keep to: the one q lies on, unless the camera's ray to the
        // surface point crossed the face's plane within a cell of q, beside the point. Then the
        // face blocks nothing there (the camera sees the point through it): a wall snapped to a
        // face up to half a cell from where it stands, and the few centimetres between put the
        // points of the walls meeting it on its far side, where the light of the wall's outside
        // showed as a bright line along the corner.
        float plane = base[a] + 0.5;
        bool upperHome = f[a] >= 0.5;
        bool cameraAbove = camera[a] >= plane;
        if (upperHome != cameraAbove && (pt[a] >= plane) == upperHome && open < 1.0) {
            vec3 crossing = mix(camera, pt, (plane - camera[a]) / (pt[a] - camera[a]));
            vec3 away = abs(crossing - t);
            away[a] = 0.0;
            if (max(away.x, max(away.y, away.z)) <= 1.0) upperHome = cameraAbove;
        }
        f[a] = upperHome ? 1.0 - (1.0 - f[a]) * open : f[a] * open;
    }
    return origin.xyz + (base + f + 0.5) * origin.w;
}

#ifdef GATHER
// gi.gather (gi/VplGather.h): the three finest cascades' propagated first bounce, kept apart
// (bindings 21-29), which the lookup takes out of their light, and the VPL gather that replaces
// it (binding 30), interleaved over 4 x 4 texels.
#include "gathered_cascades.glsl"
layout(binding = 21) uniform sampler3D first0r;
layout(binding = 22) uniform sampler3D first0g;
layout(binding = 23) uniform sampler3D first0b;
layout(binding = 24) uniform sampler3D first1r;
layout(binding = 25) uniform sampler3D first1g;
layout(binding = 26) uniform sampler3D first1b;
layout(binding = 27) uniform sampler3D first2r;
layout(binding = 28) uniform sampler3D first2g;
layout(binding = 29) uniform sampler3D first2b;
layout(binding = 30) uniform sampler2D gatheredLight;

// Cascade c's (a constant, below GATHERED_CASCADES) first bounce at uvw against `lobe`, as
// radiance.
vec3 firstBounceAt(int c, vec3 uvw, vec4 lobe) {
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return vec3(0.0);
    vec3 e = c == 0   ? projectVolumes(first0r, first0g, first0b, uvw, lobe, encodeRangeOf(0))
             : c == 1 ? projectVolumes(first1r, first1g, first1b, uvw, lobe, encodeRangeOf(1))
                      : projectVolumes(first2r, first2g, first2b, uvw, lobe, encodeRangeOf(2));
    return max(e, vec3(0.0)) / (lookup.gridOrigin[c].w * lookup.gridOrigin[c].w);
}

// The gather at this texel, averaged over the 4 x 4 block around it (one texel of each
// interleaving phase) where the neighbours lie on the same surface: normals within about 25
// degrees and positions within 2% of the view distance of the texel's tangent plane. A neighbour's
// share of VPLs lights its own point; on one surface the light varies slowly enough to average.
vec3 gatheredAround(ivec2 texel, vec3 p, vec3 n, float viewDistance) {
    ivec2 size = textureSize(gatheredLight, 0);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    int col = lookup.pixels.w;
    for (int y = -2; y <= 1; ++y)
        for (int x = -2; x <= 1; ++x) {
            ivec2 t = clamp(texel + ivec2(x, y), ivec2(0), size - 1);
            ivec2 source = min(t * lookup.pixels.x, lookup.pixels.yz - 1);
            float depth = texelFetch(depthTexture, source, 0).r;
            if (depth >= 1.0) continue;
            vec2 uv = (vec2(source) + 0.5) / vec2(lookup.pixels.yz);
            vec4 world = MUL_COLUMNS_AT(lookup.invViewProjection, col, vec4(uv * 2.0 - 1.0, depth, 1.0));
            vec3 q = world.xyz / world.w;
            vec3 m = normalize(texelFetch(normalTexture, source, 0).xyz);
            if (dot(n, m) < 0.9 || abs(dot(q - p, n)) > 0.02 * viewDistance) continue;
            sum += texelFetch(gatheredLight, t, 0).rgb;
            weights += 1.0;
        }
    return sum / max(weights, 1.0);
}
#endif

// Cascade c's irradiance alone at point p, for the damping's sample behind the surface.
vec3 irradianceAt(int c, vec3 p, vec4 cosine) {
    vec3 uvw = uvwIn(c, p);
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return vec3(0.0);
    vec3 e = projectCascade(c, uvw, cosine, encodeRangeOf(c));
    return max(e, vec3(0.0)) / (lookup.gridOrigin[c].w * lookup.gridOrigin[c].w);
}

// Cascade c's light at surface point p: half a cell out along n, damped.
CascadeSample surfaceLight(int c, vec3 p, vec3 n, LookupLobes lobes) {
    float cell = lookup.gridOrigin[c].w;
    vec3 q = p + 0.5 * cell * n;
    if (((int(lookup.encode.z) >> c) & 1) != 0) q = keptInside(c, q, p);
    // The damping's sample behind the surface stays a plain lookup: it is there to see the light
    // beyond the surface.
    CascadeSample front = lightAt(c, q, lobes);
    float damping = 1.0;
    if (lookup.grid.z != 0) {
        vec3 behind = irradianceAt(c, p - 0.5 * cell * n, lobes.irradiance);
        float f = dot(front.irradiance, vec3(0.2126, 0.7152, 0.0722));
        float bk = dot(behind, vec3(0.2126, 0.7152, 0.0722));
        float growth = max(bk - f, 0.0) / max(bk, 1e-6);
        damping = clamp(1.0 - lookup.intensity.y * growth, 0.0, 1.0);
        front.irradiance *= damping;
        front.glossy *= damping;
    }
#ifdef GATHER
    // The first bounce leaves the gathered cascades' irradiance (damped as the rest was); the
    // gather brings it back (main). The glossy term keeps the volume's.
    if (c < GATHERED_CASCADES) {
        vec3 first = firstBounceAt(c, uvwIn(c, q), lobes.irradiance);
        front.irradiance = max(front.irradiance - damping * first, vec3(0.0));
    }
#endif
    return front;
}

float insideness(int c, vec3 p) {
    return cascadeInsideness(lookup.gridOrigin[c], lookup.grid.x, lookup.encode.y, p);
}

// Cascade c's share where p lies in its blend band: 1 inside the band, 0 at its border.
float blendWeight(int c, vec3 p) { return smoothstep(0.0, 1.0, clamp(insideness(c, p), 0.0, 1.0)); }

CascadeSample mixSamples(CascadeSample a, CascadeSample b, float w) {
    return CascadeSample(a.irradiance + w * b.irradiance, a.glossy + w * b.glossy);
}

void main() {
    // This texel answers for G-buffer pixel texel x divisor (gi.resolution; the lighting pass
    // rebuilds the pixels between).
    ivec2 source = min(ivec2(gl_FragCoord.xy) * lookup.pixels.x, lookup.pixels.yz - 1);
    vec2 uv = (vec2(source) + 0.5) / vec2(lookup.pixels.yz);
    float depth = texelFetch(depthTexture, source, 0).r;
    if (depth >= 1.0) {
        outIrradiance = vec4(0.0);
        outGlossy = vec4(0.0);
        return;
    }
    vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    // The camera matrix's columns at an index the compiler cannot fold (pixels.w is 0;
    // MUL_COLUMNS_AT): read at constant offsets, it made lavapipe recompile this shader on every
    // frame the camera moved (600-850 ms a frame with a cold shader cache, against 45 ms).
    int col = lookup.pixels.w;
    vec4 world = MUL_COLUMNS_AT(lookup.invViewProjection, col, clip);
    vec3 p = world.xyz / world.w;
    vec4 normalRoughness = texelFetch(normalTexture, source, 0);
    vec3 n = normalize(normalRoughness.xyz);

    // The lobes: incoming light travels against n, so the irradiance integrates the cosine lobe
    // around -n; the glossy term evaluates each channel at its lobe's mean direction. With
    // gi.glossy off it is the cosine lobe's mean radiance, E / pi, as a rough lobe would gather:
    // no fetches beyond the irradiance's (the lobes' albedo and table fetches would raise
    // lpv_bench's CryEngine 3 setup from 2.47 to 2.81 ms predicted on Xbox 360).
    vec4 cosine = shCosineLobe(-n);
    LookupLobes lobes = LookupLobes(cosine, cosine / PI, cosine / PI, cosine / PI);
    if (lookup.intensity.z != 0.0) {
        vec3 v = normalize(lookup.cameraPosition.xyz - p);
        float roughness = clamp(normalRoughness.w, 0.0, 1.0);
        vec4 albedoMetal = texelFetch(albedoTexture, source, 0);
        vec3 f0 = mix(vec3(0.04), albedoMetal.rgb, albedoMetal.a); // as the lighting pass
        GlossyLobes glossy = glossyLobesAt(specularAlbedoTable, n, v, roughness, f0);
        lobes.glossyR = glossy.r, lobes.glossyG = glossy.g, lobes.glossyB = glossy.b;
    }
#ifdef CASCADE
    // One class's draw: the classification chose the cascade and whether the texel is in its band
    // (the next coarser cascade holds the whole band, so it answers the rest unblended).
    CascadeSample light = surfaceLight(CASCADE, p, n, lobes);
#if BLEND
    float w = blendWeight(CASCADE, p);
    light = mixSamples(CascadeSample(vec3(0.0), vec3(0.0)), light, w);
    light = mixSamples(light, surfaceLight(CASCADE + 1, p, n, lobes), 1.0 - w);
#endif
#else
    // Finest first, each cascade gets the share of the answer its blend weight gives it of what
    // the finer ones left; a point past a cascade's blend band (weight 1) leaves nothing for the
    // coarser ones, so a pixel looks up one cascade, or two in a band. (Equal to folding from the
    // coarsest in, mix by mix.) CASCADES is compile-time, so each lookup names its own textures:
    // a dynamic cascade index would make a CPU rasterizer run every branch for every pixel.
    CascadeSample light = CascadeSample(vec3(0.0), vec3(0.0));
    float left = 1.0;
#if CASCADES > 1
    {
        float w = blendWeight(0, p);
        if (w > 0.0) light = mixSamples(light, surfaceLight(0, p, n, lobes), w);
        left = 1.0 - w;
    }
#endif
#if CASCADES > 2
    if (left > 0.0) {
        float w = blendWeight(1, p);
        if (w > 0.0) light = mixSamples(light, surfaceLight(1, p, n, lobes), left * w);
        left *= 1.0 - w;
    }
#endif
#if CASCADES > 3
    if (left > 0.0) {
        float w = blendWeight(2, p);
        if (w > 0.0) light = mixSamples(light, surfaceLight(2, p, n, lobes), left * w);
        left *= 1.0 - w;
    }
#endif
    if (left > 0.0) light = mixSamples(light, surfaceLight(CASCADES - 1, p, n, lobes), left);
#endif
#ifdef GATHER
    light.irradiance += gatheredAround(ivec2(gl_FragCoord.xy), p, n, length(p - lookup.cameraPosition.xyz));
#endif
    // The view depth (1 / world.w: clip w is the view depth), for the lighting pass's rebuild.
    outIrradiance = vec4(light.irradiance, 1.0 / world.w);
    // The pixel's normal, for the lighting pass's rebuild (IndirectLighting.h).
    outGlossy = vec4(light.glossy, packRebuildNormal(n));
}
