// Multiple bounces, the sum (gi/MultipleBounces.h): a further bounce's propagated light is added
// to the cascade's result, or (FROM_FIRST) the result is the first bounce's light, kept apart, plus
// the further bounce's. Included by the generated lpv_bounce_add_<format>[_first].comp (SH_FORMAT:
// the result's storage format).
#include "lpv_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform Add {
    ivec4 grid;  // x: cells per axis
    vec4 encode; // x: the cascade's rgba8 range (LpvVolumes::injectedEncodeRange); y: 1 when encoded (the reflection's)
} params;
layout(binding = 1) uniform sampler3D bounceRed;
layout(binding = 2) uniform sampler3D bounceGreen;
layout(binding = 3) uniform sampler3D bounceBlue;
layout(binding = 4, SH_FORMAT) uniform image3D resultRed;
layout(binding = 5, SH_FORMAT) uniform image3D resultGreen;
layout(binding = 6, SH_FORMAT) uniform image3D resultBlue;
#ifdef FROM_FIRST
layout(binding = 7) uniform sampler3D firstRed;
layout(binding = 8) uniform sampler3D firstGreen;
layout(binding = 9) uniform sampler3D firstBlue;
#define BASE(name, image, c) texelFetch(first##name, c, 0)
#else
#define BASE(name, image, c) imageLoad(image, c)
#endif

#include "result_sh.glsl"
vec4 decoded(vec4 v) { return loadResultSh(v, params.encode.x); }
vec4 encoded(vec4 v) { return storeResultSh(v, params.encode.x); }

void main() {
    const ivec3 c = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(c, ivec3(params.grid.x)))) return;
    imageStore(resultRed, c, encoded(decoded(BASE(Red, resultRed, c)) + decoded(texelFetch(bounceRed, c, 0))));
    imageStore(resultGreen, c,
               encoded(decoded(BASE(Green, resultGreen, c)) + decoded(texelFetch(bounceGreen, c, 0))));
    imageStore(resultBlue, c, encoded(decoded(BASE(Blue, resultBlue, c)) + decoded(texelFetch(bounceBlue, c, 0))));
}
