#version 450
// RSM texel: world normal (facing the light) and reflected flux = albedo x irradiance x texel area.
// The texel's projected area is fixed by the fit to the volume, so the weight does not depend on
// the RSM or volume size (Kaplanyan 2009).
layout(binding = 0, std140) uniform Rsm {
    mat4 lightViewProjection;
    vec4 lightDirection;
    vec4 fluxScale;
} rsm;
layout(binding = 1, std140) uniform Draw {
    mat4 model;
    mat4 normalMatrix;
    vec4 baseColor;
    vec4 emissive;
    vec4 material;
} draw;
layout(binding = 2) uniform sampler2D baseColorTexture;

layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec2 vUv;
layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outFlux;

void main() {
    vec3 n = normalize(vNormal);
    // Two-sided: the side the light sees.
    if (dot(n, rsm.lightDirection.xyz) > 0.0) n = -n;
    vec3 albedo = draw.baseColor.rgb;
    if (draw.material.w > 0.5) albedo *= texture(baseColorTexture, vUv).rgb;
    // Metals (material.x) reflect no diffuse light: no VPL, and no albedo for the bounces.
    albedo *= 1.0 - draw.material.x;
    outNormal = vec4(n, 1.0);
    outFlux = vec4(albedo * rsm.fluxScale.rgb, 1.0);
}
