// Multiple bounces, the sum (gi/MultipleBounces.h): a further bounce's propagated light is added
// to the cascade's result, or (FROM_FIRST) the result is the first bounce's light, kept apart, plus
// the further bounce's; with KEEP, the sum is written to a second set too. Included by the generated
// lpv_bounce_add_<format>[_first][_keep].comp (SH_FORMAT: the result's storage format).
#include "lpv_common.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform Add {
    ivec4 grid;  // x: cells per axis
    vec4 encode; // x: the cascade's rgba8 range (LpvVolumes::injectedEncodeRange); y: 1 when encoded (the reflection's)
} params;
#ifdef KEEP
// gi.gather with its second bounce gathered too: the sum is also kept apart, for the lookup to take
// out (LightPropagationVolume::firstBounce). Storage images below 8 (rhi/Shader.h).
layout(binding = 1, SH_FORMAT) uniform writeonly image3D keepRed;
layout(binding = 2, SH_FORMAT) uniform writeonly image3D keepGreen;
layout(binding = 3, SH_FORMAT) uniform writeonly image3D keepBlue;
#define BOUNCE_BINDING 10
#else
#define BOUNCE_BINDING 1
#endif
layout(binding = BOUNCE_BINDING) uniform sampler3D bounceRed;
layout(binding = BOUNCE_BINDING + 1) uniform sampler3D bounceGreen;
layout(binding = BOUNCE_BINDING + 2) uniform sampler3D bounceBlue;
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
    const vec4 red = encoded(decoded(BASE(Red, resultRed, c)) + decoded(texelFetch(bounceRed, c, 0)));
    const vec4 green = encoded(decoded(BASE(Green, resultGreen, c)) + decoded(texelFetch(bounceGreen, c, 0)));
    const vec4 blue = encoded(decoded(BASE(Blue, resultBlue, c)) + decoded(texelFetch(bounceBlue, c, 0)));
    imageStore(resultRed, c, red);
    imageStore(resultGreen, c, green);
    imageStore(resultBlue, c, blue);
#ifdef KEEP
    imageStore(keepRed, c, red);
    imageStore(keepGreen, c, green);
    imageStore(keepBlue, c, blue);
#endif
}
