// The LPV frame: RSM, VPL clustering, injection, propagation, lookup, debug views.
#include "gi/LightPropagationVolume.h"

#include "EngineShaders.h"
#include "GiShaders.h"
#include "engine/profiler/FrameProfiler.h"
#include "gi/GiBudget.h"
#include "gi/GiWork.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <optional>

namespace lpv::gi {
namespace {

struct ClusterUniforms {
    glm::mat4 invLightViewProjection;
    glm::ivec4 sizes;
};

struct LookupUniforms {
    glm::mat4 invViewProjection;
    glm::vec4 gridOrigin;
    glm::ivec4 grid;
    glm::vec4 encode;
    glm::vec4 intensity;
};

struct SliceUniforms {
    glm::vec4 params;
    glm::ivec4 flags;
};

} // namespace

VolumeGrid placeVolume(const LpvSettings& s, glm::vec3 cameraPosition, glm::vec3 cameraForward,
                       const engine::Bounds& bounds) {
    VolumeGrid g;
    g.size = s.gridSize;
    g.cellSize = s.cellSize;
    const float extent = s.cellSize * float(s.gridSize);
    glm::vec3 center = cameraPosition + glm::normalize(cameraForward) * (0.25f * extent);
    if (!bounds.empty()) {
        for (int a = 0; a < 3; ++a) {
            const float lo = bounds.min[a], hi = bounds.max[a];
            if (hi - lo <= extent)
                center[a] = 0.5f * (lo + hi);
            else
                center[a] = std::clamp(center[a], lo + 0.5f * extent, hi - 0.5f * extent);
        }
    }
    // Whole cells: the volume moves in steps of one cell, so a static scene's lighting only
    // changes when the camera crosses a cell.
    g.origin = glm::floor((center - glm::vec3(0.5f * extent)) / s.cellSize + 0.5f) * s.cellSize;
    return g;
}

LightPropagationVolume::LightPropagationVolume(rhi::Device& device, platforms::PlatformProfile profile)
    : device_(device), profile_(std::move(profile)) {
    using namespace rhi;
    clusterPipeline_ = device.createPipeline(ComputePipelineDesc{&shaders::vpl_cluster_comp, "vpl cluster"});
    GraphicsPipelineDesc lookup;
    lookup.vertex = &engine::shaders::fullscreen_vert;
    lookup.fragment = &shaders::lpv_lookup_frag;
    lookup.colorFormats = {Format::RGBA16F};
    lookup.debugName = "lpv lookup";
    lookupPipeline_ = device.createPipeline(lookup);
    GraphicsPipelineDesc slice = lookup;
    slice.fragment = &shaders::lpv_slice_frag;
    slice.colorFormats = {Format::RGBA8Srgb};
    slice.debugName = "lpv slice view";
    slicePipeline_ = device.createPipeline(slice);
    GraphicsPipelineDesc points;
    points.vertex = &shaders::vpl_points_vert;
    points.fragment = &shaders::vpl_points_frag;
    points.topology = PrimitiveTopology::PointList;
    points.colorFormats = {Format::RGBA8Srgb};
    points.debugName = "vpl view";
    pointsPipeline_ = device.createPipeline(points);
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linearSampler_ = device.createSampler(linear);
}

LightPropagationVolume::~LightPropagationVolume() {
    release();
    for (auto p : {lookupPipeline_, slicePipeline_, pointsPipeline_})
        device_.destroy(p);
    device_.destroy(clusterPipeline_);
    device_.destroy(pointSampler_);
    device_.destroy(linearSampler_);
}

void LightPropagationVolume::release() {
    device_.waitIdle();
    rsm_.reset();
    volumes_.reset();
    pointLights_.reset();
    if (vpls_) device_.destroy(vpls_);
    vpls_ = {};
    made_ = false;
}

void LightPropagationVolume::remake(const LpvSettings& s) {
    release();
    rsm_ = std::make_unique<ReflectiveShadowMap>(device_, s.rsmSize);
    volumes_ = std::make_unique<LpvVolumes>(device_, s);
    pointLights_ = std::make_unique<PointLightInjection>(device_, s);
    vpls_ = device_.createBuffer({uint64_t(s.vplCount) * 48, rhi::kBufferStorage | rhi::kBufferTransfer,
                                  rhi::MemoryAccess::GpuOnly, "vpls", "gi.vpl"});
    made_ = true;
}

void LightPropagationVolume::update(const engine::Config& config, const engine::Renderer& renderer,
                                    const engine::CameraMatrices& camera) {
    const LpvSettings s = readLpvSettings(config);
    renderer_ = &renderer;
    const bool resized =
        !made_ || s.rsmSize != settings_.rsmSize || s.vplCount != settings_.vplCount || !volumes_->matches(s);
    if (s.enabled && resized) {
        checkGiBudget(s, profile_); // throws before anything changes
        remake(s);
    }
    settings_ = s;
    analyticLights_ = analyticLightsEnabled(config);
    grid_ = placeVolume(s, camera.position, camera.forward, renderer.sceneBounds());
}

void LightPropagationVolume::renderIndirect(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                                            const engine::GBufferView& gbuffer, rhi::TextureHandle target,
                                            engine::FrameProfiler* profiler) {
    using namespace rhi;
    if (!settings_.enabled || !made_ || !renderer_ || !renderer_->scene()) {
        cmd.clearTexture(target, {0, 0, 0, 0}); // GI off: no indirect light at all
        return;
    }
    const auto scope = [&](const char* name) {
        return profiler ? std::optional<engine::FrameProfiler::Scope>(profiler->scope(name, &cmd))
                        : std::nullopt;
    };
    const auto work = [&](const engine::WorkCounts& w) {
        if (profiler) profiler->setWork(w);
    };
    const engine::SunLight& sun = renderer_->sun();
    const glm::vec3 lightDir = glm::normalize(sun.direction);
    auto giScope = scope("gi");
    cmd.beginMarker("gi");
    {
        auto s = scope("rsm");
        rsm_->fit(grid_, lightDir);
        rsm_->render(cmd, *renderer_->scene(), lightDir, sun.radiance);
        work(rsmWork(settings_, renderer_->scene()->triangleCount()));
    }
    const uint32_t side = settings_.vplGridSide();
    {
        auto s = scope("vpl");
        ClusterUniforms u;
        u.invLightViewProjection = glm::inverse(rsm_->lightViewProjection());
        u.sizes = glm::ivec4(int(rsm_->size()), int(side), int(rsm_->size() / side), 0);
        cmd.bindPipeline(clusterPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindTexture(1, rsm_->depth(), pointSampler_);
        cmd.bindTexture(2, rsm_->normal(), pointSampler_);
        cmd.bindTexture(3, rsm_->flux(), pointSampler_);
        cmd.bindStorageBuffer(4, vpls_);
        cmd.dispatch((side + 7) / 8, (side + 7) / 8, 1);
        work(vplClusterWork(settings_));
    }
    {
        auto s = scope("inject");
        volumes_->inject(cmd, vpls_, settings_.vplCount, grid_, lightDir, settings_.intensity);
        work(injectWork(settings_));
    }
    {
        auto s = scope("propagate");
        volumes_->propagate(cmd, settings_.iterations);
        work(propagateWork(settings_));
    }
    if (analyticLights_) {
        // Point and spot lights, added already propagated (gi/AnalyticLight.h).
        auto s = scope("lights");
        const uint32_t n =
            pointLights_->inject(cmd, renderer_->punctualLights(), *volumes_, grid_, settings_.intensity);
        work(analyticLightsWork(settings_, n, pointLights_->cellEvaluations()));
    }
    {
        auto s = scope("lookup");
        LookupUniforms u;
        u.invViewProjection = camera.invViewProjection;
        u.gridOrigin = glm::vec4(grid_.origin, grid_.cellSize);
        u.grid = glm::ivec4(int(grid_.size), volumes_->encoded() ? 1 : 0, settings_.damping ? 1 : 0, 0);
        u.encode = glm::vec4(volumes_->encodeRange(), 0, 0, 0);
        u.intensity = glm::vec4(settings_.intensity, 1.0f, 0, 0);
        RenderPassDesc pass;
        pass.colors[0] = {target, 0, 0, LoadOp::DontCare};
        pass.colorCount = 1;
        pass.debugName = "lpv lookup";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(lookupPipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        cmd.bindTexture(1, gbuffer.depth, pointSampler_);
        cmd.bindTexture(2, gbuffer.normal, pointSampler_);
        for (uint32_t c = 0; c < 3; ++c)
            cmd.bindTexture(3 + c, volumes_->accumulated()[c], linearSampler_);
        cmd.draw(3);
        cmd.endRenderPass();
        work(lookupWork(settings_, uint64_t(gbuffer.width) * gbuffer.height));
    }
    cmd.endMarker();
}

void LightPropagationVolume::renderDebugOverlay(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                                                rhi::TextureHandle output) {
    using namespace rhi;
    if (!settings_.enabled || !made_ || settings_.debugView == GiDebugView::None ||
        settings_.debugView == GiDebugView::Indirect)
        return;
    const TextureDesc& d = device_.desc(output);
    RenderPassDesc pass;
    pass.colors[0] = {output, 0, 0, LoadOp::Load};
    pass.colorCount = 1;
    pass.debugName = "gi debug view";
    cmd.beginRenderPass(pass);
    if (settings_.debugView == GiDebugView::VolumeSlice) {
        // The slice in the top-left corner, one square of half the frame height.
        const float side = float(d.height) * 0.5f;
        cmd.setViewport({0, 0, side, side, 0, 1});
        SliceUniforms u;
        const uint32_t slice = std::min(settings_.debugSlice, grid_.size - 1);
        u.params = glm::vec4((float(slice) + 0.5f) / float(grid_.size),
                             1.0f / (grid_.cellSize * grid_.cellSize), volumes_->encodeRange(), 0);
        u.flags = glm::ivec4(volumes_->encoded() ? 1 : 0, 0, 0, 0);
        cmd.bindPipeline(slicePipeline_);
        cmd.pushUniforms(0, &u, sizeof(u));
        for (uint32_t c = 0; c < 3; ++c)
            cmd.bindTexture(1 + c, volumes_->accumulated()[c], pointSampler_);
        cmd.draw(3);
    } else {
        cmd.bindPipeline(pointsPipeline_);
        cmd.pushUniforms(0, &camera.viewProjection, sizeof(camera.viewProjection));
        cmd.bindStorageBuffer(1, vpls_);
        cmd.draw(settings_.vplCount);
    }
    cmd.endRenderPass();
}

} // namespace lpv::gi
