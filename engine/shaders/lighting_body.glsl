// Deferred lighting into the HDR target: the shadowed sun, punctual lights, emissive, and the
// indirect irradiance (filled by the GI, or the ambient constant) times SSAO. Lambertian diffuse
// (none for metals) under a GGX specular layer from the sun and the lights, plus the indirect
// light's glossy radiance weighted by the GGX lobe's directional albedo; the diffuse base keeps
// what the specular layer does not reflect (glTF's fresnel_mix, with the mixed F0 of glTF's sample
// implementation for partly metallic surfaces). Two variants
// (engine/CMakeLists.txt): `lighting` for frames where no punctual light has a shadow map, and
// `lighting_shadowed` (LIGHT_SHADOWS) with the lights' shadow atlas; the renderer picks one per
// frame. With the shadow lookups compiled in, even unexecuted, llvmpipe's lighting pass took 30%
// longer in the atrium, which has no punctual light at all.
#include "common.glsl"
#include "rebuild_normal.glsl"
#include "specular_albedo.glsl"

struct PunctualLight {
    vec4 positionRange;      // xyz position, w range (0: infinite)
    vec4 colorIntensity;     // rgb color, w intensity (candela)
    vec4 directionType;      // xyz direction the light travels, w: 1 point, 2 spot
    vec4 cone;               // x cos(outer), y cos(inner)
};

layout(binding = 1) uniform sampler2D albedoTexture;
layout(binding = 2) uniform sampler2D normalTexture;
layout(binding = 3) uniform sampler2D emissiveTexture;
layout(binding = 4) uniform sampler2D depthTexture;
layout(binding = 5) uniform sampler2DShadow shadowMap;
layout(binding = 6) uniform sampler2D aoTexture;
layout(binding = 7) uniform sampler2D indirectTexture;
layout(binding = 8, std430) readonly buffer Lights {
    PunctualLight lights[];
};
layout(binding = 9) uniform sampler2D glossyTexture;
// engine/render/SpecularAlbedo.h's table (specular_albedo.glsl): the weight's scale and bias.
layout(binding = 12) uniform sampler2D specularAlbedoTexture;
// The medium's in-scattered radiance (rgb) and transmittance (a), IndirectLighting::renderMedium.
layout(binding = 13) uniform sampler2D mediumTexture;
#ifdef LIGHT_SHADOWS
// Spot and point lights with a shadow map this frame (LightShadows): views in tiles of one atlas.
layout(binding = 10, std140) uniform LightShadows {
    mat4 viewProjection[16];
    vec4 tile[16];   // per view: xy its corner in the atlas, zw its size (uv)
    ivec4 light[6];  // per light: x its index in the list above, y its first view, z views (1 or 6)
    vec4 params[6];  // per light: x a texel's side at 1 m from the light
    ivec4 count;     // x: lights with a map
} shadows;
layout(binding = 11) uniform sampler2DShadow shadowAtlas;
#endif

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;

// The indirect irradiance and glossy radiance (IndirectLighting.h) of this pixel. With smaller indirect targets
// (frame.counts.w = divisor > 1; texel t holds the answer for pixel t * divisor) a joint bilateral
// filter rebuilds it from the four nearest texels: bilinear weights times how well each texel's
// own pixel matches this one's surface (its distance from this pixel's tangent plane, relative to
// the viewing distance, and the agreement of the normals). Light then stays on its side of
// silhouettes and creases, where plain bilinear filtering would mix a wall's light into the floor.
// Each texel carries its own pixel's view depth and normal (the two targets' alphas), so the
// rebuild reads two texels per neighbour and nothing of the G-buffer.
struct IndirectLight {
    vec3 irradiance;
    vec3 glossy;
};

IndirectLight indirectAt(vec3 p, vec3 n) {
    int divisor = frame.counts.w;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (divisor <= 1) return IndirectLight(texelFetch(indirectTexture, pixel, 0).rgb, texelFetch(glossyTexture, pixel, 0).rgb);
    ivec2 lowSize = textureSize(indirectTexture, 0);
    ivec2 fullSize = ivec2(frame.viewport.xy);
    ivec2 base = pixel / divisor;
    vec2 f = vec2(pixel - base * divisor) / float(divisor);
    // 1% of the viewing distance: the tangent-plane tolerance grows with the pixel footprint.
    float tolerance = 0.01 * max(length(p - frame.cameraPosition.xyz), 1e-3);
    vec3 sumIrradiance = vec3(0.0), plainIrradiance = vec3(0.0);
    vec3 sumGlossy = vec3(0.0), plainGlossy = vec3(0.0);
    float sum = 0.0;
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 t = min(base + o, lowSize - 1);
        ivec2 source = min(t * divisor, fullSize - 1);
        float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        vec4 et = texelFetch(indirectTexture, t, 0);
        vec3 e = et.rgb;
        vec4 g = texelFetch(glossyTexture, t, 0);
        plainIrradiance += bilinear * e;
        plainGlossy += bilinear * g.rgb;
        if (et.a <= 0.0) continue; // sky: no surface, no light
        // The texel's point from its view depth (alpha, IndirectLighting's contract): along the ray
        // through its pixel, a point h at any depth has view depth 1 / h.w, and the point scales
        // linearly with view depth from the camera.
        vec4 h = frame.invViewProjection * vec4((vec2(source) + 0.5) * frame.viewport.zw * 2.0 - 1.0, 0.5, 1.0);
        vec3 q = frame.cameraPosition.xyz + (h.xyz / h.w - frame.cameraPosition.xyz) * (et.a * h.w);
        vec3 m = unpackRebuildNormal(g.a); // its pixel's normal (IndirectLighting.h)
        float plane = abs(dot(q - p, n)) / tolerance;
        float w = bilinear * exp(-plane * plane) * pow(max(dot(m, n), 0.0), 16.0) + 1e-6 * bilinear;
        sumIrradiance += w * e;
        sumGlossy += w * g.rgb;
        sum += w;
    }
    // No neighbour on this surface (a sliver thinner than a texel): plain bilinear filtering.
    if (sum <= 1e-4) return IndirectLight(plainIrradiance, plainGlossy);
    return IndirectLight(sumIrradiance / sum, sumGlossy / sum);
}

// The medium along this pixel's ray (rgb: in-scattered radiance, a: transmittance). From a smaller
// target (frame.medium.x = divisor > 1) it is rebuilt from the four nearest texels: bilinear weights
// times how well each texel's pixel's distance from the camera matches this pixel's, so fog in
// front of a near object does not take the far wall's thicker fog. The sky matches only the sky.
vec4 mediumAt(float depth) {
    int divisor = frame.medium.x;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (divisor <= 1) return texelFetch(mediumTexture, pixel, 0);
    ivec2 lowSize = textureSize(mediumTexture, 0);
    ivec2 fullSize = ivec2(frame.viewport.xy);
    ivec2 base = pixel / divisor;
    vec2 f = vec2(pixel - base * divisor) / float(divisor);
    bool sky = depth >= 1.0;
    float distance = sky ? 0.0 : length(worldFromDepth(vUv, depth) - frame.cameraPosition.xyz);
    vec4 sum = vec4(0.0), plain = vec4(0.0);
    float weights = 0.0;
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        ivec2 t = min(base + o, lowSize - 1);
        ivec2 source = min(t * divisor, fullSize - 1);
        float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        vec4 m = texelFetch(mediumTexture, t, 0);
        plain += bilinear * m;
        float d = texelFetch(depthTexture, source, 0).r;
        float match;
        if (sky || d >= 1.0) {
            match = (sky && d >= 1.0) ? 1.0 : 0.0;
        } else {
            vec2 uv = (vec2(source) + 0.5) * frame.viewport.zw;
            float e = (length(worldFromDepth(uv, d) - frame.cameraPosition.xyz) - distance) / (0.02 * distance + 1e-4);
            match = exp(-e * e);
        }
        float w = bilinear * match;
        sum += w * m;
        weights += w;
    }
    // No neighbour at this distance (a sliver thinner than a texel): plain bilinear filtering.
    return weights > 1e-4 ? sum / weights : plain;
}

// The lit surface (or sky) seen through the medium; with render.debug_view=fog, the medium's light alone.
vec3 throughMedium(vec3 color, float depth, int debugView) {
    if (frame.medium.x <= 0) return debugView == 9 ? vec3(0.0) : color;
    vec4 m = mediumAt(depth);
    return debugView == 9 ? m.rgb : color * m.a + m.rgb;
}

float sunShadow(vec3 p, vec3 n) {
    // Offset along the normal against acne on slopes (scaled down in tiny scenes); the pipeline
    // bias handles the rest.
    vec4 s = frame.sunViewProjection * vec4(p + n * frame.sunRadiance.w, 1.0);
    vec3 c = s.xyz / s.w;
    vec2 uv = c.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || c.z > 1.0) return 1.0;
    // 3x3 PCF of hardware-filtered compares.
    float texel = 1.0 / float(frame.counts.z);
    float lit = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) lit += texture(shadowMap, vec3(uv + vec2(x, y) * texel, c.z - frame.sunDirection.w));
    return lit / 9.0;
}

#ifdef LIGHT_SHADOWS
// View `view`'s shadow at p: 3x3 PCF of hardware-filtered compares inside its tile; outside the
// view, lit (a spot's cone falloff is zero there; a point light's faces cover every direction).
float shadowInView(int view, float texelAtMetre, vec3 p, vec3 n, float distance) {
    // A texel grows with distance from the light: offset along the normal by one and a half of
    // them against acne, the pipeline's slope bias handles the rest.
    vec4 s = shadows.viewProjection[view] * vec4(p + n * (1.5 * texelAtMetre * distance), 1.0);
    if (s.w <= 0.0) return 1.0;
    vec3 c = s.xyz / s.w;
    vec2 uv = c.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || c.z > 1.0) return 1.0;
    vec4 tile = shadows.tile[view];
    vec2 step = 1.0 / vec2(textureSize(shadowAtlas, 0));
    // The taps stay inside the tile: its neighbours hold other views.
    vec2 lo = tile.xy + 1.5 * step, hi = tile.xy + tile.zw - 1.5 * step;
    vec2 at = clamp(tile.xy + uv * tile.zw, lo, hi);
    float lit = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) lit += texture(shadowAtlas, vec3(at + vec2(x, y) * step, c.z));
    return lit / 9.0;
}

// The face of a point light's cube (+x, -x, +y, -y, +z, -z) that direction d (from the light) lies in.
int cubeFace(vec3 d) {
    vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
    return d.z >= 0.0 ? 4 : 5;
}

// Whether light i of the list has a shadow map this frame.
bool hasShadowMap(int i) {
    for (int k = 0; k < shadows.count.x; ++k)
        if (shadows.light[k].x == i) return true;
    return false;
}
#endif

// The surface a pixel shows, as the direct lights see it.
struct Surface {
    vec3 n, v;           // normal, direction to the eye
    vec3 f0;             // specular reflectance at normal incidence
    float alpha2;        // GGX alpha squared (alpha = roughness^2, as glTF defines it)
    float k;             // Smith-Schlick masking constant, alpha / 2 (SpecularAlbedo.h's model)
    float maskView;      // the view's masking term over n.v: G1(v) / (n.v)
};

// How a surface answers light from direction l, per unit irradiance (irradiance holds n.l).
struct Response {
    vec3 specular; // GGX D x Smith-Schlick G x Schlick F / (4 n.l n.v): the lobe the glossy weight integrates
    vec3 diffuse;  // 1 - F: what the specular layer lets through to the diffuse base (glTF's fresnel_mix)
};

Response responseTo(Surface s, vec3 l) {
    float nl = dot(s.n, l);
    if (nl <= 0.0) return Response(vec3(0.0), vec3(0.0));
    vec3 h = normalize(l + s.v);
    float nh = max(dot(s.n, h), 0.0), vh = max(dot(s.v, h), 0.0);
    float denom = nh * nh * (s.alpha2 - 1.0) + 1.0;
    float d = s.alpha2 / (PI * denom * denom);
    float maskLight = 1.0 / (nl * (1.0 - s.k) + s.k); // G1(l) / (n.l)
    vec3 fresnel = s.f0 + (1.0 - s.f0) * pow(1.0 - vh, 5.0);
    return Response(fresnel * (d * maskLight * s.maskView * 0.25), 1.0 - fresnel);
}

// What a punctual light gives the surface: the irradiance its diffuse base keeps (after the
// specular layer's Fresnel) and the specular radiance reflected toward the eye.
struct LightArrival {
    vec3 diffuseIrradiance;
    vec3 specular;
};

// What punctual light l gives surface s at p, unshadowed: inverse square, the range's window, a
// spot's cone.
LightArrival punctualArrival(PunctualLight l, vec3 p, Surface s) {
    vec3 n = s.n;
    vec3 toLight = l.positionRange.xyz - p;
    float d2 = max(dot(toLight, toLight), 1e-4);
    vec3 dir = toLight * inversesqrt(d2);
    float atten = 1.0 / d2;
    if (l.positionRange.w > 0.0) {
        float ratio = sqrt(d2) / l.positionRange.w;
        atten *= clamp(1.0 - ratio * ratio * ratio * ratio, 0.0, 1.0);
    }
    if (l.directionType.w > 1.5) atten *= smoothstep(l.cone.x, l.cone.y, dot(-dir, l.directionType.xyz));
    vec3 e = l.colorIntensity.rgb * l.colorIntensity.w * atten * max(dot(n, dir), 0.0);
    Response r = responseTo(s, dir);
    return LightArrival(e * r.diffuse, e * r.specular);
}

void main() {
    float depth = textureLod(depthTexture, vUv, 0.0).r;
    int debugView = int(frame.params.w);
    if (depth >= 1.0) {
        vec3 sky = debugView == 0 ? vec3(0.02, 0.025, 0.03) : vec3(0.0);
        outColor = vec4(debugView == 0 || debugView == 9 ? throughMedium(sky, depth, debugView) : sky, 1.0);
        return;
    }
    vec3 p = worldFromDepth(vUv, depth);
    vec4 albedoMetal = textureLod(albedoTexture, vUv, 0.0);
    vec3 albedo = albedoMetal.rgb;
    vec3 n = normalize(textureLod(normalTexture, vUv, 0.0).xyz);
    float ao = textureLod(aoTexture, vUv, 0.0).r;
    IndirectLight light = indirectAt(p, n);
    float shadow = sunShadow(p, n);

    // Metals reflect no diffuse light (glTF's metallic-roughness model; the RSMs leave them out of
    // the GI's VPLs likewise); F0 is 4% for dielectrics, the albedo for metals.
    vec3 diffuseColor = albedo * (1.0 - albedoMetal.a);
    float roughness = clamp(textureLod(normalTexture, vUv, 0.0).a, 0.0, 1.0);
    vec3 v = normalize(frame.cameraPosition.xyz - p);
    float cosView = max(dot(n, v), 0.0);
    // The sun and the punctual lights are points: below roughness 0.1 a mirror's highlight of a
    // point is a spike narrower than a pixel, so the direct lobe keeps at least that width.
    float alpha = max(roughness, 0.1) * max(roughness, 0.1);
    float maskK = 0.5 * alpha;
    Surface surface = Surface(n, v, mix(vec3(0.04), albedo, albedoMetal.a), alpha * alpha, maskK,
                              1.0 / (max(cosView, 1e-4) * (1.0 - maskK) + maskK));

    vec3 L = -frame.sunDirection.xyz;
    vec3 sunIrradiance = frame.sunRadiance.rgb * max(dot(n, L), 0.0) * shadow;
    Response sunResponse = responseTo(surface, L);
    vec3 irradiance = sunIrradiance * sunResponse.diffuse; // what the diffuse base receives
    vec3 specular = sunIrradiance * sunResponse.specular;
#ifdef LIGHT_SHADOWS
    // The lights without a shadow map this frame, then those with one.
    for (int i = 0; i < frame.counts.x; ++i) {
        if (hasShadowMap(i)) continue;
        LightArrival a = punctualArrival(lights[i], p, surface);
        irradiance += a.diffuseIrradiance;
        specular += a.specular;
    }
    for (int k = 0; k < shadows.count.x; ++k) {
        ivec4 s = shadows.light[k];
        PunctualLight l = lights[s.x];
        vec3 fromLight = p - l.positionRange.xyz;
        int view = s.z == 6 ? s.y + cubeFace(fromLight) : s.y;
        LightArrival a = punctualArrival(l, p, surface);
        float lit = shadowInView(view, shadows.params[k].x, p, n, length(fromLight));
        irradiance += a.diffuseIrradiance * lit;
        specular += a.specular * lit;
    }
#else
    for (int i = 0; i < frame.counts.x; ++i) {
        LightArrival a = punctualArrival(lights[i], p, surface);
        irradiance += a.diffuseIrradiance;
        specular += a.specular;
    }
#endif
    vec3 direct = diffuseColor / PI * irradiance + specular;
    // Glossy: the radiance the lobe gathers (the GI's march around the mirror direction, or its
    // lookup's lobe-mean reflection; the ambient constant / pi without GI), times the fraction the
    // lobe sends to the eye, F0 x scale + bias (the split sum, SpecularAlbedo.h). The diffuse base
    // gets 1 - that fraction of the indirect light: the usual split-sum stand-in for the 1 - F the
    // direct lights take above (it also gives the base what the lobe's masking loses).
    vec2 scaleBias = specularAlbedoAt(specularAlbedoTexture, cosView, roughness, 0).rg;
    vec3 specularAlbedo = surface.f0 * scaleBias.x + scaleBias.y;
    vec3 glossy = specularAlbedo * light.glossy * ao;
    vec3 indirect = diffuseColor / PI * light.irradiance * (1.0 - specularAlbedo) * ao;
    vec3 emissive = textureLod(emissiveTexture, vUv, 0.0).rgb;

    vec3 color = direct + indirect + glossy + emissive;
    if (debugView == 1) color = albedo;
    else if (debugView == 2) color = n * 0.5 + 0.5;
    else if (debugView == 3) color = vec3(length(p - frame.cameraPosition.xyz) / 50.0);
    else if (debugView == 4) color = vec3(ao);
    else if (debugView == 5) color = vec3(shadow);
    else if (debugView == 6) color = indirect;  // linear indirect diffuse alone, as added above
    else if (debugView == 7) color = glossy;    // linear glossy reflection alone, as added above
    else if (debugView == 8) color = specular;  // linear direct specular alone (sun and lights)
    if (debugView == 0 || debugView == 9) color = throughMedium(color, depth, debugView);
    outColor = vec4(color, 1.0);
}
