#version 450
#extension GL_GOOGLE_include_directive : require
// RSM texel: world normal (facing the light) and reflected flux = diffuse albedo x the share the
// specular layer lets through (rsm_diffuse.glsl) x irradiance x texel area. The texel's projected
// area is fixed by the fit to the volume, so the weight does not depend on the RSM or volume size
// (Kaplanyan 2009).
#include "rsm_diffuse.glsl"
#include "rsm_light_facing.glsl"
layout(binding = 0, std140) uniform Rsm {
    mat4 lightViewProjection;
    vec4 lightDirection;
    vec4 fluxScale;
} rsm;
#include "draw_uniforms.glsl"
layout(binding = 2) uniform sampler2D baseColorTexture;
layout(binding = 4) uniform sampler2D metallicRoughnessTexture;

layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec2 vUv;
layout(location = DRAW_INDEX_LOCATION) flat in uint vDrawIndex;
layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outFlux;

void main() {
    DrawRecord draw = drawRecords.draws[vDrawIndex];
    vec3 n = normalize(vNormal);
    // Two-sided: the side the light sees; where a face turned toward it lies in the same plane,
    // that face.
    bool facesLight = dot(n, rsm.lightDirection.xyz) <= 0.0;
    writeLightFacingDepth(facesLight);
    if (!facesLight) n = -n;
    vec3 base = draw.baseColor.rgb;
    if (draw.material.w > 0.5) base *= texture(baseColorTexture, vUv).rgb;
    vec4 material = draw.material; // metallic as the G-buffer has it: the factor times the map's B
    if (draw.maps.x > 0.5) material.x *= texture(metallicRoughnessTexture, vUv).b;
    outNormal = vec4(n, 1.0);
    outFlux = vec4(diffuseReflectance(base, material, -dot(n, rsm.lightDirection.xyz)) * rsm.fluxScale.rgb,
                   1.0);
}
