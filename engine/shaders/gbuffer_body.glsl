// G-buffer: albedo (sRGB target) + metallic, world normal + roughness, emissive. Two variants
// (engine/CMakeLists.txt): `gbuffer` for materials with at most base colour and normal maps, and
// `gbuffer_mapped` (MATERIAL_MAPS) for those with a metallic-roughness or emissive map, whose factors
// it scales by them (glTF: metallic in B, roughness in G of one linear map). With the maps' code in
// every draw, even where the flags skipped it, llvmpipe's G-buffer pass took 15% longer in the
// atrium, which has none.
#include "common.glsl"

#define DRAW_MATERIAL_IN
#include "draw_uniforms.glsl"
layout(binding = 2) uniform sampler2D baseColorTexture;
layout(binding = 3) uniform sampler2D normalTexture;
#ifdef MATERIAL_MAPS
layout(binding = 4) uniform sampler2D metallicRoughnessTexture;
layout(binding = 5) uniform sampler2D emissiveTexture;
#endif

layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec2 vUv;
layout(location = 2) in vec4 vTangent;
layout(location = 3) in vec3 vWorld;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outEmissive;

void main() {
    DrawMaterial draw = drawMaterial();
    vec4 albedo = draw.baseColor;
    if (draw.material.w > 0.5) albedo *= texture(baseColorTexture, vUv);
    vec3 n = normalize(vNormal);
    // Two-sided: thin geometry (cloth) shows its camera-facing side, whatever its winding.
    if (dot(n, frame.cameraPosition.xyz - vWorld) < 0.0) n = -n;
    if (draw.material.z > 0.5) {
        vec3 t = normalize(vTangent.xyz - n * dot(n, vTangent.xyz));
        vec3 b = cross(n, t) * vTangent.w;
        vec3 m = texture(normalTexture, vUv).xyz * 2.0 - 1.0;
        n = normalize(m.x * t + m.y * b + m.z * n);
    }
    float metallic = draw.material.x, roughness = draw.material.y;
    vec3 emissive = draw.emissive.rgb;
#ifdef MATERIAL_MAPS
    if (draw.maps.x > 0.5) {
        vec4 mr = texture(metallicRoughnessTexture, vUv);
        metallic *= mr.b;
        roughness *= mr.g;
    }
    if (draw.maps.y > 0.5) emissive *= texture(emissiveTexture, vUv).rgb;
#endif
    outAlbedo = vec4(albedo.rgb, metallic);
    outNormal = vec4(n, roughness);
    outEmissive = vec4(emissive, 0.0);
}
