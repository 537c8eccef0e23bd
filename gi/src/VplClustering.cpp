// The VPL clustering pass: one compute dispatch over the blocks of an RSM.
#include "gi/VplClustering.h"

#include "GiShaders.h"

#include <glm/matrix.hpp>
#include <glm/vec4.hpp>

namespace lpv::gi {
namespace {

// std140 block `Params` of vpl_cluster.comp.
struct ClusterUniforms {
    glm::mat4 invLightViewProjection;
    glm::ivec4 sizes;
    glm::ivec4 options;
};

} // namespace

VplClustering::VplClustering(rhi::Device& device, const char* debugName) : device_(device) {
    using namespace rhi;
    pipeline_ = device.createPipeline(ComputePipelineDesc{&shaders::vpl_cluster_comp, debugName});
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
}

VplClustering::~VplClustering() {
    device_.destroy(pipeline_);
    device_.destroy(pointSampler_);
}

void VplClustering::record(rhi::CommandList& cmd, const ReflectiveShadowMap& rsm, uint32_t side,
                           rhi::BufferHandle vpls, rhi::BufferHandle gatherVpls) {
    ClusterUniforms u;
    u.invLightViewProjection = glm::inverse(rsm.lightViewProjection());
    u.sizes = glm::ivec4(int(rsm.size()), int(side), int(rsm.size() / side), 0);
    u.options = glm::ivec4(gatherVpls ? 1 : 0, 0, 0, 0);
    cmd.bindPipeline(pipeline_);
    cmd.pushUniforms(0, &u, sizeof(u));
    cmd.bindTexture(1, rsm.depth(), pointSampler_);
    cmd.bindTexture(2, rsm.normal(), pointSampler_);
    cmd.bindTexture(3, rsm.flux(), pointSampler_);
    cmd.bindStorageBuffer(4, vpls);
    cmd.bindStorageBuffer(5, gatherVpls ? gatherVpls : vpls); // unwritten without the gather's
    cmd.dispatch((side + 7) / 8, (side + 7) / 8, 1);
}

} // namespace lpv::gi
