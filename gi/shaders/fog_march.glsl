// The fog march (gi/FogMarch.h). Per texel, the camera ray to its pixel's surface (or out of the
// scene's bounds) is cut into fog.steps segments; each segment's medium is taken as constant at a
// point jittered inside it, and its in-scattering integrated in closed form,
//   S x (1 - exp(-sigma_t dt)) / sigma_t,
// so a homogeneous medium lit uniformly comes out exact at any step count. S is sigma_s times
//   the sun: its irradiance x phase(cos) x its shadow-map visibility (single scattering, the shafts);
//   the LPV: the phase function convolved with the radiance field. For Henyey-Greenstein the
//     convolution scales SH band l by g^l (Funk-Hecke), so the radiance scattered toward the camera
//     is the intensity SH evaluated at that direction with band 1 times g, over the cell's
//     cross-section (as the lookup turns intensity into radiance).
// The jitter is interleaved gradient noise of the pixel, fixed over time: a still camera sees a
// still image. Compiled per cascade count (CASCADES 0..4; 0: the sun alone, no volumes bound).
#include "lpv_common.glsl"
#if CASCADES > 0
#include "lpv_cascades.glsl"
#endif

layout(binding = 0, std140) uniform Fog {
    mat4 invViewProjection;
    mat4 sunViewProjection;
    vec4 cameraPosition; // xyz; w: the sun shadow's depth bias
    vec4 sunDirection;   // xyz: where the sun's light travels; w: Henyey-Greenstein g
    vec4 sunRadiance;    // rgb: irradiance facing the sun; w: 1 with a shadow map
    vec4 scattering;     // rgb: single-scattering albedo; w: extinction per metre at the base height
    vec4 height;         // x: height falloff per metre, y: base height, z: gi.rgba8_range
    vec4 boundsMin;      // the scene's bounds: where rays that meet no surface stop
    vec4 boundsMax;
    vec4 gridOrigin[4];  // per cascade: xyz corner of cell 0, w: cell size
    ivec4 pixels;        // x: resolution divisor, y: steps, zw: G-buffer size
    ivec4 grid;          // x: cells per axis, y: volumes rgba8-encoded, z: cascades
} fog;
layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2DShadow sunShadowMap;

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outMedium;

// Henyey-Greenstein: the share of light travelling along a scattered into b, cos = dot(a, b).
float henyeyGreenstein(float cosine, float g) {
    float d = 1.0 + g * g - 2.0 * g * cosine;
    return (1.0 - g * g) / (4.0 * PI * d * sqrt(d));
}

// Extinction per metre at height y: fog.density up to the base height, thinning exponentially above.
float extinctionAt(float y) {
    return fog.scattering.w * exp(-fog.height.x * max(y - fog.height.y, 0.0));
}

float sunVisibility(vec3 x) {
    if (fog.sunRadiance.w == 0.0) return 1.0;
    vec4 s = fog.sunViewProjection * vec4(x, 1.0);
    vec3 c = s.xyz / s.w;
    vec2 uv = c.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || c.z > 1.0) return 1.0;
    // An explicit LOD: the map has one level, and inside the march implicit derivatives are undefined.
    return textureLod(sunShadowMap, vec3(uv, c.z - fog.cameraPosition.w), 0.0);
}

#if CASCADES > 0
// Whether cascade c holds x (c constant in every call).
bool insideCascade(int c, vec3 x) {
    vec3 uvw = uvwInVolume(fog.gridOrigin[c], fog.grid.x, x);
    return all(greaterThanEqual(uvw, vec3(0.0))) && all(lessThanEqual(uvw, vec3(1.0)));
}

// Cascade c's radiance at x weighted by `lobe` (the phase function toward the camera).
vec3 cascadeInScattering(int c, vec3 x, vec4 lobe) {
    vec3 uvw = uvwInVolume(fog.gridOrigin[c], fog.grid.x, x);
    float range = fog.grid.y != 0 ? cascadeRange(fog.gridOrigin[c], fog.height.z) : 0.0;
    float cell = fog.gridOrigin[c].w;
    return max(projectCascade(c, uvw, lobe, range), vec3(0.0)) / (cell * cell);
}
#endif

// The LPV's radiance at x, phase-weighted toward the camera: the finest cascade holding x answers.
vec3 indirectInScattering(vec3 x, vec4 lobe) {
#if CASCADES > 0
    if (insideCascade(0, x)) return cascadeInScattering(0, x, lobe);
#endif
#if CASCADES > 1
    if (insideCascade(1, x)) return cascadeInScattering(1, x, lobe);
#endif
#if CASCADES > 2
    if (insideCascade(2, x)) return cascadeInScattering(2, x, lobe);
#endif
#if CASCADES > 3
    if (insideCascade(3, x)) return cascadeInScattering(3, x, lobe);
#endif
    return vec3(0.0);
}

// Where the ray from o along unit d leaves the box (0 when it misses it).
float exitDistance(vec3 o, vec3 d) {
    vec3 inv = 1.0 / d;
    vec3 a = (fog.boundsMin.xyz - o) * inv, b = (fog.boundsMax.xyz - o) * inv;
    vec3 far = max(a, b), near = min(a, b);
    float tFar = min(min(far.x, far.y), far.z), tNear = max(max(near.x, near.y), near.z);
    return tFar >= max(tNear, 0.0) ? tFar : 0.0;
}

void main() {
    ivec2 source = min(ivec2(gl_FragCoord.xy) * fog.pixels.x, fog.pixels.zw - 1);
    vec2 uv = (vec2(source) + 0.5) / vec2(fog.pixels.zw);
    float depth = texelFetch(depthTexture, source, 0).r;
    vec3 o = fog.cameraPosition.xyz;
    vec4 far = fog.invViewProjection * vec4(uv * 2.0 - 1.0, depth >= 1.0 ? 0.5 : depth, 1.0);
    vec3 toFar = far.xyz / far.w - o;
    vec3 d = normalize(toFar);
    float rayLength = depth >= 1.0 ? exitDistance(o, d) : sqrt(dot(toFar, toFar));

    float g = fog.sunDirection.w;
    // The light scattered toward the camera travels along -d.
    vec3 sunScattered = fog.sunRadiance.rgb * henyeyGreenstein(dot(fog.sunDirection.xyz, -d), g);
    vec4 lobe = shBasis(-d) * vec4(1.0, g, g, g);
    int steps = max(fog.pixels.y, 1);
    float dt = rayLength / float(steps);
    float jitter = fract(52.9829189 * fract(dot(vec2(source), vec2(0.06711056, 0.00583715))));
    vec3 inScattered = vec3(0.0);
    float transmittance = 1.0;
    for (int i = 0; i < steps; ++i) {
        vec3 x = o + d * (dt * (float(i) + jitter));
        float sigmaT = extinctionAt(x.y);
        vec3 scattered = fog.scattering.rgb * (sunScattered * sunVisibility(x) + indirectInScattering(x, lobe));
        float segment = exp(-sigmaT * dt);
        // sigma_s x L x (1 - T) / sigma_t with sigma_s = albedo x sigma_t: the sigma_t cancel.
        inScattered += transmittance * scattered * (1.0 - segment);
        transmittance *= segment;
    }
    outMedium = vec4(inScattered, transmittance);
}
