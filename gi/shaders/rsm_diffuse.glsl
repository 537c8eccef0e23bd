// What an RSM texel's surface reflects diffusely of the light it receives, in every direction: its
// diffuse colour (base colour x (1 - metallic), none for metals) times the share glTF's fresnel_mix
// leaves the diffuse base, as engine/shaders/lighting_body.glsl shows the direct light: 1 - F(v.h)
// toward each view, (1 - F0) x (1 - the Schlick mean at the light's angle) over them all
// (engine/render/SpecularAlbedo.h). The VPLs then carry the light the lit surfaces show.
#ifndef RSM_DIFFUSE_GLSL
#define RSM_DIFFUSE_GLSL

#include "specular_albedo.glsl"

// engine::SpecularAlbedoTexture (specular_albedo.glsl).
layout(binding = 3) uniform sampler2D specularAlbedoTable;

// `material`: the draw's x metallic (engine::DrawUniforms). `cosLight`: the normal (facing the
// light) against the direction to the light.
vec3 diffuseReflectance(vec3 base, vec4 material, float cosLight) {
    float metallic = material.x;
    vec3 f0 = mix(vec3(0.04), base, metallic);
    float schlickMean = specularAlbedoAt(specularAlbedoTable, cosLight, 0.0, 1).z;
    return base * (1.0 - metallic) * (1.0 - f0) * (1.0 - schlickMean);
}

#endif
