// Geometry volume from the camera's view: a regular grid of G-buffer samples, each marking its
// cell as holding a surface of its orientation (gv_inject_body.glsl says why not its area). Catches
// what the light does not see: walls in shadow, surfaces facing away from it.
#include "gv_common.glsl"

layout(binding = 1) uniform sampler2D gbufferDepth;
layout(binding = 2) uniform sampler2D gbufferNormal;
layout(binding = 3) uniform sampler2D gbufferAlbedo;

layout(location = 0) flat out vec3 vCoverage;
layout(location = 1) flat out int vFromCamera;
layout(location = 2) flat out vec3 vAlbedo;

void main() {
    ivec2 size = textureSize(gbufferDepth, 0);
    int cols = gv.grid.w;
    int rows = max(1, (cols * size.y + size.x / 2) / size.x);
    ivec2 sampleIndex = ivec2(gl_VertexIndex % cols, gl_VertexIndex / cols);
    vec2 uv = (vec2(sampleIndex) + 0.5) / vec2(cols, rows);
    ivec2 pixel = min(ivec2(uv * vec2(size)), size - 1);
    float depth = texelFetch(gbufferDepth, pixel, 0).r;
    vec3 normal = texelFetch(gbufferNormal, pixel, 0).xyz;
    // Clip space has y pointing down the image and depth 0..1 (engine/render/CameraMatrices.h).
    vec4 world = gv.invViewProjection * vec4(uv.x * 2.0 - 1.0, uv.y * 2.0 - 1.0, depth, 1.0);
    vec3 p = world.xyz / world.w;
    vCoverage = abs(normalize(normal));
    vFromCamera = 1;
    vAlbedo = texelFetch(gbufferAlbedo, pixel, 0).rgb;
    gl_PointSize = 1.0;
    bool valid = sampleIndex.y < rows && depth < 1.0 && dot(normal, normal) > 0.25;
    gl_Position = valid ? surfelPosition(p) : PARKED_POINT;
}
