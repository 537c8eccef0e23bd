// std430 array `Draws` (engine::DrawUniforms, GpuScene::drawRecords()): one record per draw of the
// scene, made once when the scene is set. A draw passes its index as its first instance and the
// vertex shader reads the record at gl_InstanceIndex, or, in a pass drawn as indirect multi-draws
// (engine::MultiDraw: GL gives gl_InstanceIndex one base per call), at the per-instance attribute
// DRAW_INDEX_ATTRIBUTE (GpuScene::drawIndices(), which the first instance offsets on both APIs):
//       layout(location = DRAW_INDEX_ATTRIBUTE) in uint inDrawIndex;
// What the fragment shader needs of it comes
// one of two ways:
// - as flat varyings (DrawMaterial), where fragments far outnumber vertices (the G-buffer): a CPU
//   rasterizer gathers a storage-buffer read lane by lane, per fragment;
//       vertex:   #define DRAW_MATERIAL_OUT before including this file; writeDrawMaterial(draw);
//       fragment: #define DRAW_MATERIAL_IN; DrawMaterial draw = drawMaterial();
// - by the draw's index, a flat varying at DRAW_INDEX_LOCATION, where there are few fragments per
//   vertex (the RSMs), so four more varyings a vertex would cost more than the reads they save;
//       vertex:   layout(location = DRAW_INDEX_LOCATION) flat out uint vDrawIndex;
//                 vDrawIndex = uint(gl_InstanceIndex);
//       fragment: layout(location = DRAW_INDEX_LOCATION) flat in uint vDrawIndex;
//                 DrawRecord draw = drawRecords.draws[vDrawIndex];
// (Measurements: docs/benchmarks.md, "Per-draw records".)
#ifndef DRAW_UNIFORMS_GLSL
#define DRAW_UNIFORMS_GLSL

#define DRAW_INDEX_LOCATION 7
// engine::kDrawIndexAttribute
#define DRAW_INDEX_ATTRIBUTE 6
// The first of DrawMaterial's four flat varyings.
#define DRAW_MATERIAL_LOCATION 8

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

// What a fragment shader reads of its draw's record.
struct DrawMaterial {
    vec4 baseColor;
    vec4 emissive;
    vec4 material;
    vec4 maps;
};

#if defined(DRAW_MATERIAL_OUT)
layout(location = DRAW_MATERIAL_LOCATION) flat out vec4 vDrawBaseColor;
layout(location = DRAW_MATERIAL_LOCATION + 1) flat out vec4 vDrawEmissive;
layout(location = DRAW_MATERIAL_LOCATION + 2) flat out vec4 vDrawMaterial;
layout(location = DRAW_MATERIAL_LOCATION + 3) flat out vec4 vDrawMaps;
void writeDrawMaterial(DrawRecord draw) {
    vDrawBaseColor = draw.baseColor;
    vDrawEmissive = draw.emissive;
    vDrawMaterial = draw.material;
    vDrawMaps = draw.maps;
}
#elif defined(DRAW_MATERIAL_IN)
layout(location = DRAW_MATERIAL_LOCATION) flat in vec4 vDrawBaseColor;
layout(location = DRAW_MATERIAL_LOCATION + 1) flat in vec4 vDrawEmissive;
layout(location = DRAW_MATERIAL_LOCATION + 2) flat in vec4 vDrawMaterial;
layout(location = DRAW_MATERIAL_LOCATION + 3) flat in vec4 vDrawMaps;
DrawMaterial drawMaterial() { return DrawMaterial(vDrawBaseColor, vDrawEmissive, vDrawMaterial, vDrawMaps); }
#endif

#endif
