// Shared by the renderer's shaders: the per-frame block and helpers. Binding 0 is always Frame.
#ifndef LPV_COMMON_GLSL
#define LPV_COMMON_GLSL

layout(binding = 0, std140) uniform Frame {
    mat4 viewProjection;
    mat4 invViewProjection;
    mat4 view;
    mat4 sunViewProjection;  // shadow map space: xy in [-1, 1], depth in [0, 1]
    vec4 cameraPosition;     // xyz
    vec4 sunDirection;       // xyz: direction the light travels; w: shadow bias (depth units)
    vec4 sunRadiance;        // rgb: irradiance on a surface facing the sun; w: shadow normal offset (m)
    vec4 ambient;            // rgb: constant indirect irradiance when no GI fills the indirect target
    vec4 viewport;           // width, height, 1/width, 1/height
    vec4 params;             // x: exposure, y: ssao radius (m), z: ssao strength, w: debug view
    ivec4 counts;            // x: punctual light count, y: ssao enabled, z: shadow map size, w: indirect targets' resolution divisor
    ivec4 medium;            // x: the medium target's resolution divisor, 0: no medium (IndirectLighting::mediumDivisor)
} frame;

const float PI = 3.14159265358979;

// World position from a depth-buffer value at a texture coordinate (row 0 at the top = NDC y -1).
vec3 worldFromDepth(vec2 uv, float depth) {
    vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    vec4 world = frame.invViewProjection * clip;
    return world.xyz / world.w;
}

#endif
