// std430 array `Draws` (engine::DrawUniforms, GpuScene::drawRecords()): one record per draw of the
// scene, made once when the scene is set. A draw passes its index as its first instance; the
// vertex shader reads the record at gl_InstanceIndex and hands the index to the fragment shader
// as the flat varying at DRAW_INDEX_LOCATION:
//     vertex:   layout(location = DRAW_INDEX_LOCATION) flat out uint vDrawIndex;
//               vDrawIndex = uint(gl_InstanceIndex);  DrawRecord draw = drawRecords.draws[gl_InstanceIndex];
//     fragment: layout(location = DRAW_INDEX_LOCATION) flat in uint vDrawIndex;
//               DrawRecord draw = drawRecords.draws[vDrawIndex];
#ifndef DRAW_UNIFORMS_GLSL
#define DRAW_UNIFORMS_GLSL

#define DRAW_INDEX_LOCATION 7

struct DrawRecord {
    mat4 model;
    mat4 normalMatrix;
    vec4 baseColor;
    vec4 emissive;
    vec4 material; // x metallic, y roughness, z has a normal map, w has a base colour texture
    vec4 maps;     // x has a metallic-roughness map (roughness G, metallic B), y has an emissive map
};

layout(binding = 1, std430) readonly buffer Draws {
    DrawRecord draws[];
} drawRecords;

#endif
