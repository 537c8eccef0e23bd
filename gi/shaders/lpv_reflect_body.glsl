// Multiple bounces, the reflection step (gi/MultipleBounces.h): what a bounce's accumulated light
// loses at the geometry volume's faces is reflected by the surfels there and becomes the next
// bounce's injection. Per cell and per direction e of its six faces:
//   flux toward e   = what propagation hands the neighbour at cell + e, as a flux
//                     (its L0 / Y0; the transfer of PropagationScheme.h with one side only),
//   blocked         = (1 - face transmittance) x that flux (what the occlusion pass took away),
//   reflected       = albedo x blocked, re-emitted as a clamped-cosine lobe toward -e, back into
//                     this cell: half a cell in front of the blocking face, the safety distance
//                     that keeps a surfel from lighting itself (Kaplanyan & Dachsbacher 2010).
// Reflection is linear, so reflecting the sum of every iteration's light (the accumulated result)
// is reflecting each iteration's light in turn, which is what the paper does inside propagation.
// Included by the generated lpv_reflect_<format>.comp (INJECT_FORMAT: the injection volume's).
#include "lpv_common.glsl"
#include "propagation_transfer.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform Reflect {
    ivec4 grid;  // x: cells per axis
    vec4 encode; // x: the cascade's rgba8 range (LpvVolumes::injectedEncodeRange); y: 1 when encoded
    // xyz: where cell c's light is in the source, c + shift (a source computed a frame earlier,
    // where the volume was placed then; 0 otherwise); beyond it there is none.
    ivec4 shift;
} params;
layout(binding = 4) uniform sampler3D sourceRed;
layout(binding = 5) uniform sampler3D sourceGreen;
layout(binding = 6) uniform sampler3D sourceBlue;
layout(binding = 7) uniform sampler3D faceTransmittance; // xyz: the cell's -x, -y, -z faces
layout(binding = 8) uniform sampler3D surfelAlbedo;      // rgb: mean albedo of the cell's surfels
// Storage images below kPortableStorageImageBindings (rhi/Shader.h), which every device has.
layout(binding = 1, INJECT_FORMAT) uniform writeonly image3D injectedRed;
layout(binding = 2, INJECT_FORMAT) uniform writeonly image3D injectedGreen;
layout(binding = 3, INJECT_FORMAT) uniform writeonly image3D injectedBlue;


vec4 source(sampler3D s, ivec3 c) {
    const ivec3 k = c + params.shift.xyz;
    if (any(lessThan(k, ivec3(0))) || any(greaterThanEqual(k, ivec3(params.grid.x)))) return vec4(0.0);
    vec4 v = texelFetch(s, k, 0);
    return params.encode.y != 0.0 ? decodeShRange(v, params.encode.x) : v;
}

void main() {
    const ivec3 c = ivec3(gl_GlobalInvocationID);
    const int n = params.grid.x;
    if (any(greaterThanEqual(c, ivec3(n)))) return;
    // Coefficients (Y00, y, z, x), one vec4 per colour channel; L0 of the 3 channels side by side.
    const vec4 r = source(sourceRed, c), g = source(sourceGreen, c), b = source(sourceBlue, c);
    const vec3 l0 = vec3(r.x, g.x, b.x);
    // The face transmittance toward -e is the cell's own; toward +e the next cell's lower face
    // (beyond the volume nothing blocks).
    const vec3 lower = texelFetch(faceTransmittance, c, 0).xyz;
    const vec3 upper = vec3(c.x + 1 < n ? texelFetch(faceTransmittance, c + ivec3(1, 0, 0), 0).x : 1.0,
                            c.y + 1 < n ? texelFetch(faceTransmittance, c + ivec3(0, 1, 0), 0).y : 1.0,
                            c.z + 1 < n ? texelFetch(faceTransmittance, c + ivec3(0, 0, 1), 0).z : 1.0);
    const vec3 albedo = texelFetch(surfelAlbedo, c, 0).rgb;
    vec4 outR = vec4(0.0), outG = vec4(0.0), outB = vec4(0.0);
    for (int axis = 0; axis < 3; ++axis) {
        // The coefficient along this axis in (Y00, y, z, x) order.
        const int k = axis == 0 ? 3 : axis;
        const vec3 along = vec3(r[k], g[k], b[k]);
        vec3 e = vec3(0.0);
        e[axis] = 1.0;
        for (int side = 0; side < 2; ++side) {
            const float s = side == 0 ? 1.0 : -1.0; // toward +e or -e
            const float blocked = 1.0 - (side == 0 ? upper[axis] : lower[axis]);
            // L0 the neighbour at cell + s e would receive: KA l0 + s KB along (>= 0: no light
            // travels backwards to be reflected).
            const vec3 received = max(KA * l0 + s * KB * along, vec3(0.0));
            // As a lobe toward -s e with the same flux: L0 = flux x Y0 = received L0.
            const vec3 reflected = albedo * blocked * received;
            const vec4 lobe = shCosineLobe(-s * e) / SH_COS_C0;
            outR += reflected.r * lobe, outG += reflected.g * lobe, outB += reflected.b * lobe;
        }
    }
    imageStore(injectedRed, c, outR);
    imageStore(injectedGreen, c, outG);
    imageStore(injectedBlue, c, outB);
}
