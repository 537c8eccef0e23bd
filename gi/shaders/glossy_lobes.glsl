// The GGX lobe a surface reflects the volume's light with, as the lookup and the glossy march
// evaluate it. Radiance in an L1 volume is linear in the direction, so its average over the lobe
// is the field at the lobe's mean light direction m: the light directions summed with the split
// sum's weights (engine/render/SpecularAlbedo.h's table; x along n, y along the mirror direction's
// part across n), per channel of F0 = (F0 x scaleDirection + biasDirection) / (F0 x scale + bias).
// |m| < 1 narrows band 1 as the lobe widens, and m leans from the mirror direction toward n as
// roughness grows (the off-specular peak), so one basis per channel evaluates the whole lobe.
// Needs lpv_common.glsl and specular_albedo.glsl.
#ifndef GLOSSY_LOBES_GLSL
#define GLOSSY_LOBES_GLSL

struct GlossyLobes {
    vec4 r, g, b;   // per channel: the basis that evaluates the radiance arriving from m
    vec3 direction; // the mean light direction of F0's luminance, normalized: where the march goes
};

vec2 glossyMeanDirection(float f0, vec4 scaleBias, vec2 biasDirection) {
    return (f0 * scaleBias.zw + biasDirection) / max(f0 * scaleBias.x + scaleBias.y, 1e-6);
}

// Light from direction m travels along -m.
vec4 glossyLobeBasis(vec2 m, vec3 n, vec3 t) { return shBasis(-(m.x * n + m.y * t)); }

// The lobes at a surface with normal n seen from direction v (toward the eye), of `roughness` and
// reflectance f0 at normal incidence.
GlossyLobes glossyLobesAt(sampler2D table, vec3 n, vec3 v, float roughness, vec3 f0) {
    vec3 across = reflect(-v, n) - n * dot(n, v); // the mirror direction's part across n
    float acrossLength = length(across);
    vec3 t = acrossLength > 1e-5 ? across / acrossLength : vec3(0.0); // head-on the lobe is symmetric
    float cosView = max(dot(n, v), 0.0);
    vec4 scaleBias = specularAlbedoAt(table, cosView, roughness, 0);
    vec2 biasDirection = specularAlbedoAt(table, cosView, roughness, 1).xy;
    GlossyLobes lobes;
    lobes.r = glossyLobeBasis(glossyMeanDirection(f0.r, scaleBias, biasDirection), n, t);
    lobes.g = glossyLobeBasis(glossyMeanDirection(f0.g, scaleBias, biasDirection), n, t);
    lobes.b = glossyLobeBasis(glossyMeanDirection(f0.b, scaleBias, biasDirection), n, t);
    vec2 m = glossyMeanDirection(dot(f0, vec3(0.2126, 0.7152, 0.0722)), scaleBias, biasDirection);
    vec3 d = m.x * n + m.y * t;
    lobes.direction = dot(d, d) > 1e-10 ? normalize(d) : n;
    return lobes;
}

#endif
