// Intensity-aware VPL clustering (vpl_cluster.comp): each block of an RSM's texels becomes up to
// kVplsPerCluster VPLs at the flux-weighted position and normal, carrying the block's flux, so the
// injection and the geometry volume draw thousands of points rather than every texel. The sun's RSM
// is clustered once per cascade, each spot or point light's RSM once per frame (SpotLightRsms).
#pragma once

#include "gi/ReflectiveShadowMap.h"
#include "rhi/Device.h"

#include <cstdint>

namespace lpv::gi {

class VplClustering {
public:
    // `debugName`: the pipeline's, so that a capture tells the sun's clustering from the lights'.
    VplClustering(rhi::Device& device, const char* debugName);
    ~VplClustering();
    VplClustering(const VplClustering&) = delete;
    VplClustering& operator=(const VplClustering&) = delete;

    // Clusters what `rsm` last recorded into `side` x `side` blocks (`side` divides rsm.size()),
    // kVplsPerCluster slots each, in `vpls`: std430 {vec4 position (w: valid), vec4 normal, vec4 flux}.
    // Its unprojection holds for the sun's orthographic map and a light's perspective one alike.
    // With `gatherVpls` (as large), also the per-pixel gather's VPLs (VplGather), whose blocks over
    // a crease split by normal: each side lights what lies next to it as its own surface does.
    void record(rhi::CommandList& cmd, const ReflectiveShadowMap& rsm, uint32_t side, rhi::BufferHandle vpls,
                rhi::BufferHandle gatherVpls = {});

private:
    rhi::Device& device_;
    rhi::ComputePipelineHandle pipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
