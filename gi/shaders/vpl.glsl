// A VPL as the cluster pass writes it (vpl_cluster.comp, gi/VplClustering.h) and every pass that
// reads VPLs takes it; tests/gi/GpuVpls.h is its C++ twin.
#ifndef VPL_GLSL
#define VPL_GLSL
struct Vpl {
    vec4 position; // w: > 0 lit: a cluster's patch, its half extents packed (patch_form_factor.glsl);
                   // a listed face's 1 (lpv_reflect_gathered_body.glsl); 0 unlit
    vec4 normal;   // w: the share of the block's texels it holds (its share of the block's area)
    vec4 flux;     // w: RSM texels clustered
};
#endif
