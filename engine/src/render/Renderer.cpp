// The deferred renderer's passes.
#include "engine/render/Renderer.h"

#include "EngineShaders.h"
#include "engine/profiler/FrameProfiler.h"
#include "engine/render/SpecularAlbedoTexture.h"
#include "rhi/Error.h"

#define GLM_FORCE_DEPTH_ZERO_TO_ONE
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace lpv::engine {
namespace {

const IntSetting kShadowMapSize{"render.shadow_map_size", 2048, 256, 8192,
                                "Sun shadow map resolution (texels per side)"};
const IntSetting kSpotShadows{"render.spot_shadows", 2, 0, int(LightShadows::kMaxSpots),
                              "Spot lights lit per pixel that get a shadow map (those nearest and brightest "
                              "to the camera); the others are unshadowed"};
const IntSetting kPointShadows{"render.point_shadows", 1, 0, int(LightShadows::kMaxPointLights),
                               "Point lights lit per pixel that get a shadow map of six faces (those nearest "
                               "and brightest to the camera); the others are unshadowed"};
const IntSetting kLightShadowSize{"render.light_shadow_map_size", 512, 128, 2048,
                                  "Spot light shadow map and point light shadow face resolution (texels per "
                                  "side)"};
const BoolSetting kSsao{"render.ssao", true, "Screen-space ambient occlusion on the indirect light"};
const FloatSetting kSsaoRadius{"render.ssao_radius", 0.5, 0.01, 10.0, "SSAO sampling radius in metres"};
const FloatSetting kSsaoStrength{"render.ssao_strength", 1.0, 0.0, 2.0, "SSAO darkening at full occlusion"};
const FloatSetting kExposure{"render.exposure", 1.0, 0.001, 1000.0,
                             "Exposure multiplier before tone mapping"};
const Vec3Setting kAmbient{"render.ambient",
                           {0.3f, 0.32f, 0.36f},
                           0.0,
                           1000.0,
                           "Constant indirect irradiance used when GI is off (linear RGB)"};
const EnumSetting<DebugView> kDebugView{"render.debug_view",
                                        DebugView::Final,
                                        {{DebugView::Final, "final"},
                                         {DebugView::Albedo, "albedo"},
                                         {DebugView::Normals, "normals"},
                                         {DebugView::Depth, "depth"},
                                         {DebugView::Ssao, "ssao"},
                                         {DebugView::Shadow, "shadow"},
                                         {DebugView::Indirect, "indirect"},
                                         {DebugView::Glossy, "glossy"},
                                         {DebugView::Specular, "specular"},
                                         {DebugView::Fog, "fog"}},
                                        "What the frame shows; indirect = linear indirect diffuse only, "
                                        "glossy = linear glossy reflection only, specular = linear direct "
                                        "specular only (sun and lights), fog = linear light the fog scatters "
                                        "toward the camera only (fog.enabled)"};

rhi::GraphicsPipelineHandle fullscreenPipeline(rhi::Device& device, const rhi::ShaderBinary& fragment,
                                               rhi::Format format, const char* name) {
    rhi::GraphicsPipelineDesc d;
    d.vertex = &shaders::fullscreen_vert;
    d.fragment = &fragment;
    d.colorFormats = {format};
    d.debugName = name;
    return device.createPipeline(d);
}

// One fullscreen triangle into `target` with the frame's uniforms at binding 0; `bind` binds the
// pass's own inputs.
template <typename Bind>
void fullscreenPass(rhi::CommandList& cmd, rhi::TextureHandle target, rhi::GraphicsPipelineHandle pipeline,
                    const char* name, const FrameUniforms& frame, Bind&& bind) {
    rhi::RenderPassDesc pass;
    pass.colors[0] = {target, 0, 0, rhi::LoadOp::DontCare};
    pass.colorCount = 1;
    pass.debugName = name;
    cmd.beginRenderPass(pass);
    cmd.bindPipeline(pipeline);
    cmd.pushUniforms(0, &frame, sizeof(frame));
    bind();
    cmd.draw(3);
    cmd.endRenderPass();
}

WorkCounts fullscreenWork(uint64_t pixels, uint64_t texelsPerPixel, uint64_t aluPerPixel,
                          uint64_t bytesPerPixel) {
    WorkCounts w;
    w.pixelsShaded = pixels;
    w.texelsRead = pixels * texelsPerPixel;
    w.texelsWritten = pixels;
    w.aluOps = pixels * aluPerPixel;
    w.bytesMoved = pixels * bytesPerPixel;
    w.primitives = 1;
    return w;
}

} // namespace

WorkCounts indirectRebuildWork(uint64_t pixels) {
    // Neighbouring pixels share those texels, so memory traffic does not grow (the smaller
    // targets even save some); only fetches and arithmetic do.
    WorkCounts w;
    // Per neighbour: irradiance with its view depth, glossy radiance with its normal; less the two
    // texels the full-resolution path reads.
    w.texelsRead = pixels * (4 * 2 - 2);
    // About 30 operations per neighbour, and 6 more to unpack its normal.
    w.aluOps = pixels * 4 * 36;
    return w;
}

Renderer::Renderer(rhi::Device& device, uint32_t width, uint32_t height)
    : device_(device), width_(width), height_(height),
      shadowDraws_(device, "sun shadow", "render.draw_commands"),
      gbufferDraws_(device, "gbuffer", "render.draw_commands") {
    using namespace rhi;
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linear.debugName = "linear clamp";
    linearClamp_ = device.createSampler(linear);
    SamplerDesc point{Filter::Nearest, Filter::Nearest, Filter::Nearest};
    point.debugName = "point clamp";
    pointClamp_ = device.createSampler(point);
    SamplerDesc compare;
    compare.mipFilter = Filter::Nearest;
    compare.compareEnable = true;
    compare.compareOp = CompareOp::LessOrEqual;
    compare.debugName = "shadow compare";
    shadowCompare_ = device.createSampler(compare);
    // The sun's shadow map and the indirect targets wait for the first frame, which knows their
    // sizes (render.shadow_map_size, the GI's resolution): made here at the defaults and remade
    // there, they were allocated for nothing, and the profiler's peak memory counted them (16 MiB of
    // shadow map where the config asked for 0.25).
    createTargets(0);
    specularAlbedo_ = std::make_unique<SpecularAlbedoTexture>(device);
    createPipelines();
    lightShadows_ = std::make_unique<LightShadows>(device);
}

Renderer::~Renderer() {
    device_.waitIdle();
    scene_.reset();
    lightShadows_.reset();
    if (directLights_) device_.destroy(directLights_);
    destroyTargets();
    specularAlbedo_.reset();
    if (gbufferMappedPipeline_) device_.destroy(gbufferMappedPipeline_);
    for (auto p : {gbufferPipeline_, shadowPipeline_, ssaoPipeline_, ssaoBlurPipeline_, lightingPipeline_,
                   lightingShadowedPipeline_, tonemapPipeline_})
        device_.destroy(p);
    for (auto s : {linearClamp_, pointClamp_, shadowCompare_})
        device_.destroy(s);
}

void Renderer::createTargets(uint32_t shadowSize) {
    using namespace rhi;
    const auto target = [&](Format f, uint32_t extraUsage, const char* name, const char* category) {
        return device_.createTexture({TextureKind::Tex2D, f, width_, height_, 1, 1,
                                      kTextureColorTarget | kTextureSampled | extraUsage, name, category});
    };
    targets_.albedo = target(Format::RGBA8Srgb, 0, "gbuffer albedo", "render.gbuffer");
    targets_.normal = target(Format::RGBA16F, 0, "gbuffer normal", "render.gbuffer");
    targets_.emissive = target(Format::RGBA16F, 0, "gbuffer emissive", "render.gbuffer");
    targets_.depth = device_.createTexture({TextureKind::Tex2D, Format::D32F, width_, height_, 1, 1,
                                            kTextureDepthTarget | kTextureSampled | kTextureTransfer,
                                            "gbuffer depth", "render.gbuffer"});
    targets_.aoRaw = target(Format::R32F, 0, "ssao raw", "render.ssao");
    targets_.ao = target(Format::R32F, kTextureTransfer, "ssao", "render.ssao");
    if (indirectDivisor_ > 0) createIndirectTargets(indirectDivisor_);
    createMediumTarget(mediumDivisor_);
    targets_.hdr = target(Format::RGBA16F, kTextureTransfer, "hdr", "render.lighting");
    targets_.output = target(Format::RGBA8Srgb, kTextureTransfer, "output", "render.output");
    shadowSize_ = shadowSize;
    if (shadowSize > 0)
        targets_.shadow =
            device_.createTexture({TextureKind::Tex2D, Format::D32F, shadowSize, shadowSize, 1, 1,
                                   kTextureDepthTarget | kTextureSampled, "sun shadow map", "render.shadow"});
}

void Renderer::createIndirectTargets(uint32_t divisor) {
    using namespace rhi;
    indirectDivisor_ = divisor;
    const uint32_t w = (width_ + divisor - 1) / divisor, h = (height_ + divisor - 1) / divisor;
    const auto target = [&](const char* name) {
        return device_.createTexture(
            {TextureKind::Tex2D, Format::RGBA16F, w, h, 1, 1,
             kTextureColorTarget | kTextureSampled | kTextureStorage | kTextureTransfer, name,
             "render.lighting"});
    };
    targets_.indirect = target("indirect irradiance");
    targets_.glossy = target("glossy radiance");
}

void Renderer::createMediumTarget(uint32_t divisor) {
    using namespace rhi;
    // The provider's medium is one of its passes (its time is in the provider's "gi" scopes), so
    // its target counts in the GI's memory too.
    mediumDivisor_ = divisor;
    if (divisor == 0) return;
    const uint32_t w = (width_ + divisor - 1) / divisor, h = (height_ + divisor - 1) / divisor;
    targets_.medium =
        device_.createTexture({TextureKind::Tex2D, Format::RGBA16F, w, h, 1, 1,
                               kTextureColorTarget | kTextureSampled | kTextureTransfer, "medium", "gi.fog"});
}

void Renderer::destroyTargets() {
    for (auto t : {targets_.albedo, targets_.normal, targets_.emissive, targets_.depth, targets_.aoRaw,
                   targets_.ao, targets_.indirect, targets_.glossy, targets_.hdr, targets_.output,
                   targets_.shadow, targets_.medium})
        if (t) device_.destroy(t);
    targets_ = {};
}

rhi::GraphicsPipelineDesc Renderer::gbufferPipelineDesc(bool materialMaps) {
    using namespace rhi;
    GraphicsPipelineDesc g;
    g.vertex = &shaders::gbuffer_vert;
    g.fragment = materialMaps ? &shaders::gbuffer_mapped_frag : &shaders::gbuffer_frag;
    g.vertexBuffers = {{sizeof(Vertex)}};
    g.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)},
                    {1, VertexFormat::Float3, offsetof(Vertex, normal)},
                    {2, VertexFormat::Float2, offsetof(Vertex, uv)},
                    {3, VertexFormat::Float4, offsetof(Vertex, tangent)}};
    addDrawIndexStream(g);
    g.depthTest = g.depthWrite = true;
    g.depthCompare = CompareOp::Less;
    g.colorFormats = {Format::RGBA8Srgb, Format::RGBA16F, Format::RGBA16F};
    g.depthFormat = Format::D32F;
    g.debugName = materialMaps ? "gbuffer with material maps" : "gbuffer";
    return g;
}

void Renderer::createPipelines() {
    using namespace rhi;
    gbufferPipeline_ = device_.createPipeline(gbufferPipelineDesc(false));

    GraphicsPipelineDesc s;
    s.vertex = &shaders::shadow_vert;
    s.fragment = &shaders::shadow_frag;
    s.vertexBuffers = {{sizeof(Vertex)}};
    s.attributes = {{0, VertexFormat::Float3, offsetof(Vertex, position)}};
    addDrawIndexStream(s);
    s.depthTest = s.depthWrite = true;
    s.depthCompare = CompareOp::Less;
    s.depthBiasConstant = 2.0f;
    s.depthBiasSlope = 2.0f;
    s.depthFormat = Format::D32F;
    s.debugName = "sun shadow";
    shadowPipeline_ = device_.createPipeline(s);

    ssaoPipeline_ = fullscreenPipeline(device_, shaders::ssao_frag, Format::R32F, "ssao");
    ssaoBlurPipeline_ = fullscreenPipeline(device_, shaders::ssao_blur_frag, Format::R32F, "ssao blur");
    lightingPipeline_ = fullscreenPipeline(device_, shaders::lighting_frag, Format::RGBA16F, "lighting");
    lightingShadowedPipeline_ = fullscreenPipeline(device_, shaders::lighting_shadowed_frag, Format::RGBA16F,
                                                   "lighting, light shadows");
    tonemapPipeline_ = fullscreenPipeline(device_, shaders::tonemap_frag, Format::RGBA8Srgb, "tone map");
}

void Renderer::resize(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_) return;
    device_.waitIdle();
    destroyTargets();
    width_ = width;
    height_ = height;
    createTargets(shadowSize_);
}

void Renderer::setScene(const Scene& scene) {
    device_.waitIdle();
    scene_.reset();
    auto next = std::make_unique<GpuScene>(device_, scene);
    // Made for the first scene that needs it (before the scene is taken, so a failure leaves none
    // to draw without it): on llvmpipe and lavapipe the variant's mere existence added 50-200 ms to
    // the first frame's G-buffer pass of the atrium, which has no such maps.
    if (next->hasMaterialMaps() && !gbufferMappedPipeline_)
        gbufferMappedPipeline_ = device_.createPipeline(gbufferPipelineDesc(true));
    scene_ = std::move(next);
    if (directLights_) device_.destroy(directLights_);
    const uint32_t lightCount = scene_->lightCount();
    directLights_ = device_.createBuffer(
        {sizeof(GpuPunctualLight) * std::max(lightCount, 1u), rhi::kBufferStorage | rhi::kBufferTransfer,
         rhi::MemoryAccess::GpuOnly, scene.name + " directly lit lights", "scene.lights"});
    directIndices_.clear();
    directIndices_.reserve(lightCount);
    uploadedIndices_.clear();
    uploadedIndices_.reserve(lightCount);
    directRecords_.clear();
    directRecords_.reserve(lightCount);
    bounds_ = scene.bounds;
    punctualLights_.clear();
    for (const Light& l : scene.lights)
        if (l.type != LightType::Directional) punctualLights_.push_back(l);
    sceneSpots_ = scenePointLights_ = 0;
    for (const GpuPunctualLight& l : scene_->lightRecords())
        (l.directionType.w > 1.5f ? sceneSpots_ : scenePointLights_) += 1;
    // A scene without a directional light has no sun: its punctual lights alone light it (the
    // default sun, kept before, lit a room that has only a ceiling lamp).
    sun_.radiance = glm::vec3(0.0f);
    for (const Light& l : scene.lights)
        if (l.type == LightType::Directional) {
            sun_.direction = glm::normalize(l.direction);
            sun_.radiance = l.color * l.intensity;
            break;
        }
}

uint32_t Renderer::directLights(rhi::CommandList& cmd, const IndirectLighting* indirect,
                                rhi::BufferHandle& buffer) {
    const uint32_t count = scene_->lightCount();
    buffer = scene_->lights();
    if (!indirect) return count;
    directIndices_.clear(); // capacity from setScene(): no allocation
    for (uint32_t i = 0; i < count; ++i)
        if (!indirect->carriesPunctualLight(i)) directIndices_.push_back(i);
    if (directIndices_.size() == count || directIndices_.empty()) return uint32_t(directIndices_.size());
    buffer = directLights_;
    if (directIndices_ != uploadedIndices_) {
        directRecords_.clear();
        for (uint32_t i : directIndices_)
            directRecords_.push_back(scene_->lightRecords()[i]);
        cmd.updateBuffer(directLights_, 0, directRecords_.data(),
                         uint32_t(directRecords_.size() * sizeof(GpuPunctualLight)));
        uploadedIndices_ = directIndices_; // within the reserved capacity
    }
    return uint32_t(directIndices_.size());
}

GBufferView Renderer::gbuffer() const {
    return {targets_.albedo, targets_.normal, targets_.depth, targets_.ao, width_, height_};
}

void Renderer::render(rhi::CommandList& cmd, const CameraMatrices& camera, const Config& config,
                      FrameProfiler* profiler, IndirectLighting* indirect) {
    using namespace rhi;
    if (!scene_) throw Error("Renderer::render() before setScene()");
    const uint32_t wantShadow = uint32_t(config.get(kShadowMapSize));
    if (wantShadow != shadowSize_) {
        // The first frame, or a settings change, not a steady-state frame: the shadow map is
        // (re)made at its new size.
        if (targets_.shadow) device_.destroy(targets_.shadow);
        shadowSize_ = wantShadow;
        targets_.shadow =
            device_.createTexture({TextureKind::Tex2D, Format::D32F, shadowSize_, shadowSize_, 1, 1,
                                   kTextureDepthTarget | kTextureSampled, "sun shadow map", "render.shadow"});
    }

    // Sun shadow fitted to the scene bounds.
    const glm::vec3 center = bounds_.center();
    const float radius = std::max(0.5f * glm::length(bounds_.size()), 0.01f);
    const glm::vec3 dir = glm::normalize(sun_.direction);
    const glm::vec3 up = std::fabs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const glm::mat4 sunView = glm::lookAt(center - dir * radius * 2.0f, center, up);
    const glm::mat4 sunProj = glm::orthoRH_ZO(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f);

    const uint32_t divisor = indirect ? std::clamp(indirect->resolutionDivisor(), 1u, 8u) : 1u;
    if (divisor != indirectDivisor_) {
        // The first frame, or a settings change (the GI's resolution, or GI on/off), not a
        // steady-state frame.
        if (targets_.indirect) device_.destroy(targets_.indirect);
        if (targets_.glossy) device_.destroy(targets_.glossy);
        createIndirectTargets(divisor);
    }
    const uint32_t mediumDivisor = indirect ? std::min(indirect->mediumDivisor(), 8u) : 0u;
    if (mediumDivisor != mediumDivisor_) {
        // The provider's fog turned on or off or changed resolution: a settings change.
        if (targets_.medium) device_.destroy(targets_.medium);
        targets_.medium = {};
        createMediumTarget(mediumDivisor);
    }

    // As many light shadow maps as asked for, but for no more lights than the scene has and the
    // lighting pass can be left to light (memory): the atlas is remade on a settings or scene
    // change only.
    const auto limit = [&](LightType type) {
        return indirect ? indirect->perPixelLightLimit(type) : std::numeric_limits<uint32_t>::max();
    };
    const uint32_t wantSpots =
        std::min({uint32_t(config.get(kSpotShadows)), sceneSpots_, limit(LightType::Spot)});
    const uint32_t wantPoints =
        std::min({uint32_t(config.get(kPointShadows)), scenePointLights_, limit(LightType::Point)});
    const uint32_t wantTile = uint32_t(config.get(kLightShadowSize));
    if (wantSpots != lightShadows_->spotCapacity() || wantPoints != lightShadows_->pointLightCapacity() ||
        ((wantSpots > 0 || wantPoints > 0) && wantTile != lightShadows_->tileSize()))
        lightShadows_->resize(wantSpots, wantPoints, wantTile);

    const glm::vec3 ambient = config.get(kAmbient);
    frame_.viewProjection = camera.viewProjection;
    frame_.invViewProjection = camera.invViewProjection;
    frame_.view = camera.view;
    frame_.sunViewProjection = sunProj * sunView;
    frame_.cameraPosition = glm::vec4(camera.position, 1.0f);
    frame_.sunDirection = glm::vec4(dir, 0.0005f);
    // The sun shadow's offset along the normal (metres): 2 cm, or 4 of the map's texels where a
    // scene is so small that 2 cm would carry a point through its walls (a room at 1e-3 scale was
    // lit inside).
    frame_.sunRadiance = glm::vec4(sun_.radiance, std::min(0.02f, 4.0f * 2.0f * radius / float(shadowSize_)));
    frame_.ambient = glm::vec4(ambient, 0.0f);
    frame_.viewport = glm::vec4(float(width_), float(height_), 1.0f / float(width_), 1.0f / float(height_));
    frame_.params = glm::vec4(float(config.get(kExposure)), float(config.get(kSsaoRadius)),
                              float(config.get(kSsaoStrength)), float(int(config.get(kDebugView))));
    // Point and spot lights the indirect light already holds are not lit a second time.
    rhi::BufferHandle lightBuffer;
    const uint32_t directLights = this->directLights(cmd, indirect, lightBuffer);
    frame_.counts =
        glm::ivec4(int(directLights), config.get(kSsao) ? 1 : 0, int(shadowSize_), int(indirectDivisor_));
    frame_.medium = glm::ivec4(int(mediumDivisor_), 0, 0, 0);

    const uint64_t pixels = uint64_t(width_) * height_;
    const auto scope = [&](const char* name, bool gpuTimed = true) {
        return profiler
                   ? std::optional<FrameProfiler::Scope>(profiler->scope(name, gpuTimed ? &cmd : nullptr))
                   : std::nullopt;
    };
    const auto work = [&](const WorkCounts& w) {
        if (profiler) profiler->setWork(w);
    };
    {
        auto s = scope("render.shadow");
        cmd.beginMarker("sun shadow");
        RenderPassDesc pass;
        pass.depth = {targets_.shadow, 0, LoadOp::Clear, 1.0f};
        pass.debugName = "sun shadow";
        cmd.beginRenderPass(pass);
        cmd.bindPipeline(shadowPipeline_);
        cmd.pushUniforms(0, &frame_, sizeof(frame_));
        cmd.bindVertexBuffer(0, scene_->vertices());
        cmd.bindVertexBuffer(kDrawIndexSlot, scene_->drawIndices());
        cmd.bindIndexBuffer(scene_->indices(), IndexType::Uint32);
        cmd.bindStorageBuffer(1, scene_->drawRecords());
        // No textures: every draw in one multi-draw.
        shadowDraws_.reserve(uint32_t(scene_->draws().size()));
        for (const GpuDraw& d : scene_->draws())
            shadowDraws_.add(d.lods[0], d.index);
        shadowDraws_.draw(cmd);
        cmd.endRenderPass();
        cmd.endMarker();
        WorkCounts w;
        w.primitives = scene_->triangleCount();
        w.texelsWritten = uint64_t(shadowSize_) * shadowSize_;
        w.bytesMoved = w.texelsWritten * 4 + scene_->triangleCount() * 3 * sizeof(Vertex);
        work(w);
    }
    if (lightShadows_->spotCapacity() + lightShadows_->pointLightCapacity() > 0) {
        auto s = scope("render.light_shadows");
        cmd.beginMarker("light shadows");
        const std::span<const GpuPunctualLight> lit =
            lightBuffer == scene_->lights() ? std::span(scene_->lightRecords()).first(directLights)
                                            : std::span(directRecords_).first(directLights);
        lightShadows_->render(cmd, *scene_, lit, camera, bounds_);
        cmd.endMarker();
        work(lightShadows_->work());
    }
    {
        auto s = scope("render.gbuffer");
        cmd.beginMarker("gbuffer");
        RenderPassDesc pass;
        pass.colors[0] = {targets_.albedo, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
        pass.colors[1] = {targets_.normal, 0, 0, LoadOp::Clear, {0, 0, 1, 1}};
        pass.colors[2] = {targets_.emissive, 0, 0, LoadOp::Clear, {0, 0, 0, 0}};
        pass.colorCount = 3;
        pass.depth = {targets_.depth, 0, LoadOp::Clear, 1.0f};
        pass.debugName = "gbuffer";
        cmd.beginRenderPass(pass);
        // The draws without metallic-roughness or emissive maps, then those with (gbuffer_body.glsl):
        // each pipeline bound once, and a multi-draw per set of textures (a batch's draws share
        // their maps too). Equal depths keep the first draw, so where coplanar surfaces of the two
        // kinds meet, the one without maps wins rather than the earlier in the scene.
        gbufferDraws_.reserve(uint32_t(scene_->draws().size()));
        const std::vector<GpuDraw>& draws = scene_->draws();
        for (const bool mapped : {false, true}) {
            if (mapped && !scene_->hasMaterialMaps()) break;
            cmd.bindPipeline(mapped ? gbufferMappedPipeline_ : gbufferPipeline_);
            cmd.pushUniforms(0, &frame_, sizeof(frame_));
            cmd.bindVertexBuffer(0, scene_->vertices());
            cmd.bindVertexBuffer(kDrawIndexSlot, scene_->drawIndices());
            cmd.bindIndexBuffer(scene_->indices(), IndexType::Uint32);
            cmd.bindStorageBuffer(1, scene_->drawRecords());
            for (const DrawBatch& batch : scene_->batches()) {
                const GpuDraw& first = draws[scene_->batchedDraws()[batch.first]];
                if (first.hasMaterialMaps() != mapped) continue;
                for (uint32_t k = batch.first; k < batch.first + batch.count; ++k) {
                    const GpuDraw& d = draws[scene_->batchedDraws()[k]];
                    gbufferDraws_.add(d.lods[0], d.index);
                }
                cmd.bindTexture(2, first.baseColor, scene_->materialSampler());
                cmd.bindTexture(3, first.normal, scene_->materialSampler());
                if (mapped) {
                    cmd.bindTexture(4, first.metallicRoughnessMap, scene_->materialSampler());
                    cmd.bindTexture(5, first.emissiveMap, scene_->materialSampler());
                }
                gbufferDraws_.draw(cmd);
            }
        }
        cmd.endRenderPass();
        cmd.endMarker();
        WorkCounts w = fullscreenWork(pixels, 2, 40, 4 + 8 + 8 + 4);
        w.primitives = scene_->triangleCount();
        w.texelsWritten = pixels * 4;
        work(w);
    }
    {
        auto s = scope("render.ssao");
        cmd.beginMarker("ssao");
        fullscreenPass(cmd, targets_.aoRaw, ssaoPipeline_, "ssao", frame_, [&] {
            cmd.bindTexture(1, targets_.depth, pointClamp_);
            cmd.bindTexture(2, targets_.normal, pointClamp_);
        });
        fullscreenPass(cmd, targets_.ao, ssaoBlurPipeline_, "ssao blur", frame_,
                       [&] { cmd.bindTexture(1, targets_.aoRaw, pointClamp_); });
        cmd.endMarker();
        WorkCounts w = fullscreenWork(pixels, 2 + 16 + 16, 16 * 40, 4 * 34);
        w += fullscreenWork(pixels, 16, 16, 4 * 17);
        work(w);
    }
    if (indirect) {
        indirect->renderIndirect(cmd, camera, gbuffer(), targets_.indirect, targets_.glossy, profiler);
    } else {
        cmd.clearTexture(targets_.indirect, {ambient.x, ambient.y, ambient.z, 0.0f});
        // The ambient constant has no direction: a uniform sky of radiance E / pi, which every lobe
        // gathers alike.
        const glm::vec3 sky = ambient / std::numbers::pi_v<float>;
        cmd.clearTexture(targets_.glossy, {sky.x, sky.y, sky.z, 0.0f});
    }
    if (mediumDivisor_ > 0) {
        SunShadowView sun;
        sun.shadowMap = targets_.shadow;
        sun.viewProjection = frame_.sunViewProjection;
        sun.direction = glm::vec3(frame_.sunDirection);
        sun.radiance = glm::vec3(frame_.sunRadiance);
        sun.depthBias = frame_.sunDirection.w;
        indirect->renderMedium(cmd, camera, gbuffer(), sun, targets_.medium, profiler);
    }
    {
        auto s = scope("render.lighting");
        cmd.beginMarker("lighting");
        // The variant with the lights' shadow atlas only in frames where a light has a map.
        const bool lightShadows = lightShadows_->activeCount() > 0;
        fullscreenPass(cmd, targets_.hdr, lightShadows ? lightingShadowedPipeline_ : lightingPipeline_,
                       "lighting", frame_, [&] {
                           cmd.bindTexture(1, targets_.albedo, pointClamp_);
                           cmd.bindTexture(2, targets_.normal, pointClamp_);
                           cmd.bindTexture(3, targets_.emissive, pointClamp_);
                           cmd.bindTexture(4, targets_.depth, pointClamp_);
                           cmd.bindTexture(5, targets_.shadow, shadowCompare_);
                           cmd.bindTexture(6, targets_.ao, pointClamp_);
                           cmd.bindTexture(7, targets_.indirect, pointClamp_);
                           cmd.bindStorageBuffer(8, lightBuffer);
                           cmd.bindTexture(9, targets_.glossy, pointClamp_);
                           cmd.bindTexture(12, specularAlbedo_->texture(), linearClamp_);
                           // Without a medium the binding is unread (frame.medium.x = 0).
                           cmd.bindTexture(13, mediumDivisor_ > 0 ? targets_.medium : targets_.indirect,
                                           pointClamp_);
                           if (!lightShadows) return;
                           cmd.pushUniforms(10, &lightShadows_->uniforms(), sizeof(LightShadowUniforms));
                           cmd.bindTexture(11, lightShadows_->atlas(targets_.shadow), shadowCompare_);
                       });
        cmd.endMarker();
        // Each shadowed light adds its 3x3 compares where it lights (counted as every pixel); the
        // specular albedo is a bilinear fetch of four texels; GGX specular takes about 40
        // operations for the sun and for each light.
        WorkCounts w = fullscreenWork(pixels, 12 + 9 * 4 + 9 * uint64_t(lightShadows_->activeCount()),
                                      180 + 80 * uint64_t(directLights), 4 * 12 + 8);
        // The medium's rebuild: four texels and their pixels' depths, a weight each.
        if (mediumDivisor_ > 1)
            w += fullscreenWork(pixels, 8, 4 * 30, 4 * 8 + 4 * 4);
        else if (mediumDivisor_ == 1)
            w += fullscreenWork(pixels, 1, 4, 8);
        work(w);
    }
    if (indirectDivisor_ > 1) {
        // The bilateral rebuild of the pixels the GI lookup skipped runs inside the lighting pass,
        // so its time is measured there; its work is GI's (gi.resolution trades lookups for it), so
        // it goes into a GI scope of its own, timed on the CPU only (nothing is recorded in it),
        // where the predicted console GI time and the budget scheduler see it.
        auto s = scope("gi.rebuild", false);
        work(indirectRebuildWork(pixels));
        if (profiler) profiler->setTimedIn("render.lighting");
    }
    {
        auto s = scope("render.tonemap");
        cmd.beginMarker("tone map");
        fullscreenPass(cmd, targets_.output, tonemapPipeline_, "tone map", frame_,
                       [&] { cmd.bindTexture(1, targets_.hdr, pointClamp_); });
        cmd.endMarker();
        work(fullscreenWork(pixels, 1, 20, 8 + 4));
    }
    if (indirect) indirect->renderDebugOverlay(cmd, camera, targets_.output);
}

} // namespace lpv::engine
