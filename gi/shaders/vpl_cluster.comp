#version 450
#extension GL_GOOGLE_include_directive : require
// VPL down-sampling: each thread clusters one block of RSM texels into one VPL, weighting position
// and normal by the texels' flux luminance (intensity-aware clustering) and summing the flux, so
// the total reflected flux is unchanged.
#include "lpv_common.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

struct Vpl {
    vec4 position;  // w: 1 when the cluster holds any lit texel
    vec4 normal;
    vec4 flux;      // w: RSM texels clustered
};

layout(binding = 0, std140) uniform Params {
    mat4 invLightViewProjection;
    ivec4 sizes;  // x: RSM size, y: VPL grid side, z: block side, w: 0 (see below)
} params;
layout(binding = 1) uniform sampler2D rsmDepth;
layout(binding = 2) uniform sampler2D rsmNormal;
layout(binding = 3) uniform sampler2D rsmFlux;
layout(binding = 4, std430) writeonly buffer Vpls {
    Vpl vpls[];
};

void main() {
    ivec2 cluster = ivec2(gl_GlobalInvocationID.xy);
    int side = params.sizes.y;
    if (cluster.x >= side || cluster.y >= side) return;
    int block = params.sizes.z;
    float rsmSize = float(params.sizes.x);
    vec3 position = vec3(0.0), normal = vec3(0.0), flux = vec3(0.0);
    float weight = 0.0, texels = 0.0;
    // The matrix's columns at an index the compiler cannot fold (sizes.w is 0; MUL_COLUMNS_AT):
    // read at constant offsets, lavapipe recompiled this shader on every frame the sun moved
    // (90-130 ms per cascade with a cold shader cache, against 2 ms).
    const int col = params.sizes.w;
    for (int y = 0; y < block; ++y)
        for (int x = 0; x < block; ++x) {
            ivec2 t = cluster * block + ivec2(x, y);
            float depth = texelFetch(rsmDepth, t, 0).r;
            if (depth >= 1.0) continue;
            vec3 f = texelFetch(rsmFlux, t, 0).rgb;
            float w = dot(f, vec3(0.2126, 0.7152, 0.0722)) + 1e-8;
            vec4 clip = vec4((vec2(t) + 0.5) / rsmSize * 2.0 - 1.0, depth, 1.0);
            vec4 world = MUL_COLUMNS_AT(params.invLightViewProjection, col, clip);
            position += w * world.xyz / world.w;
            normal += w * texelFetch(rsmNormal, t, 0).xyz;
            flux += f;
            weight += w;
            texels += 1.0;
        }
    Vpl v;
    v.position = weight > 0.0 ? vec4(position / weight, 1.0) : vec4(0.0);
    v.normal = vec4(length(normal) > 0.0 ? normalize(normal) : vec3(0.0, 1.0, 0.0), 0.0);
    v.flux = vec4(flux, texels); // w: the texels it clusters (the geometry volume's albedo)
    vpls[cluster.y * side + cluster.x] = v;
}
