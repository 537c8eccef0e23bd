// The injection pass: the VPLs drawn as points into the injection volume, per slice or layered.
#include "gi/LpvInjection.h"

#include "GiShaders.h"

namespace lpv::gi {
namespace {

// std140 block `Inject` of inject_body.glsl.
struct InjectUniforms {
    glm::vec4 gridOrigin;
    glm::vec4 lightDirection;
    glm::vec4 intensity;
    glm::ivec4 grid;
};

} // namespace

LpvInjection::LpvInjection(rhi::Device& device, const LpvSettings& settings)
    : device_(device), gridSize_(settings.gridSize), layered_(device.caps().vertexShaderLayer) {
    using namespace rhi;
    const Format injectFormat = settings.shFormat == ShFormat::Rgba32f ? Format::RGBA32F : Format::RGBA16F;
    GraphicsPipelineDesc d;
    d.vertex = layered_ ? &shaders::inject_layered_vert : &shaders::inject_slice_vert;
    d.fragment = &shaders::inject_frag;
    d.topology = PrimitiveTopology::PointList;
    d.colorFormats = {injectFormat, injectFormat, injectFormat};
    d.blend = {BlendState::additive()};
    d.debugName = "lpv inject";
    pipeline_ = device.createPipeline(d);
}

LpvInjection::~LpvInjection() {
    device_.destroy(pipeline_);
}

void LpvInjection::record(rhi::CommandList& cmd, LpvVolumes& volumes, rhi::BufferHandle vpls,
                          uint32_t vplCount, const VolumeGrid& grid, glm::vec3 lightDirection,
                          float intensity) {
    const VplSource source{vpls, vplCount, glm::vec4(lightDirection, 0.0f)};
    record(cmd, volumes, std::span(&source, 1), grid, intensity);
}

void LpvInjection::record(rhi::CommandList& cmd, LpvVolumes& volumes, std::span<const VplSource> sources,
                          const VolumeGrid& grid, float intensity, uint32_t cascade) {
    using namespace rhi;
    const std::array<TextureHandle, 3>& injected = volumes.injected();
    volumes.setInjected(grid, cascade);
    InjectUniforms u;
    u.gridOrigin = glm::vec4(grid.origin, grid.cellSize);
    u.intensity = glm::vec4(intensity, 0, 0, 0);
    // One layered draw per source where the device lets the vertex shader pick the slice; else
    // every source once per slice (gridSize times the vertex work). Each pass clears what it draws
    // to as it begins: no clear of its own to order before it.
    const uint32_t passes = layered_ ? 1 : gridSize_;
    for (uint32_t slice = 0; slice < passes; ++slice) {
        RenderPassDesc pass;
        for (uint32_t c = 0; c < 3; ++c) {
            pass.colors[c] = {injected[c], 0, slice, LoadOp::Clear};
            pass.colors[c].layered = layered_;
        }
        pass.colorCount = 3;
        pass.debugName = layered_ ? "lpv inject" : "lpv inject slice";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(pipeline_);
        for (const VplSource& source : sources) {
            if (source.count == 0) continue;
            u.lightDirection = source.light;
            u.grid = glm::ivec4(int(gridSize_), int(slice), int(source.count), 0);
            cmd.pushUniforms(0, &u, sizeof(u));
            cmd.bindStorageBuffer(1, source.vpls);
            cmd.draw(source.count);
        }
        cmd.endRenderPass();
    }
}

} // namespace lpv::gi
