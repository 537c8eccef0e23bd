// std140 block `Draw` (engine::DrawUniforms): one per draw of the scene, the same in every stage of a
// program (GL links the stages' blocks only when they match).
#ifndef DRAW_UNIFORMS_GLSL
#define DRAW_UNIFORMS_GLSL

layout(binding = 1, std140) uniform Draw {
    mat4 model;
    mat4 normalMatrix;
    vec4 baseColor;
    vec4 emissive;
    vec4 material; // x metallic, y roughness, z has a normal map, w has a base colour texture
    vec4 maps;     // x has a metallic-roughness map (roughness G, metallic B), y has an emissive map
} draw;

#endif
