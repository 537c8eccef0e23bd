// The lookup pass: uniforms, bindings and one fullscreen triangle, or one per cascade class.
#include "gi/IndirectLookup.h"

#include "EngineShaders.h"
#include "GiShaders.h"
#include "rhi/Error.h"

#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <string>
#include <tuple>

namespace lpv::gi {
namespace {

// lpv_lookup.glsl's highest texture binding (faceTransmittance3) plus one.
constexpr uint32_t kLookupTextureBindings = 21;

void requireBindings(const rhi::Device& device, uint32_t bindings, const char* what) {
    if (device.caps().fragmentTextureBindings < bindings)
        throw rhi::Error(std::string("GI: ") + what + " binds textures up to binding " +
                         std::to_string(bindings - 1) + " in one fragment shader, and this device (" +
                         device.caps().deviceName + ") allows " +
                         std::to_string(device.caps().fragmentTextureBindings) +
                         " (OpenGL's GL_MAX_TEXTURE_IMAGE_UNITS, Vulkan's per-stage samplers)");
}

rhi::GraphicsPipelineDesc lookupDesc() {
    rhi::GraphicsPipelineDesc d;
    d.vertex = &engine::shaders::fullscreen_vert;
    d.colorFormats = {rhi::Format::RGBA16F, rhi::Format::RGBA16F}; // irradiance, glossy radiance
    d.debugName = "lpv lookup";
    return d;
}

// std140 block `Lookup` of lpv_lookup.glsl.
struct LookupUniforms {
    glm::mat4 invViewProjection;
    glm::vec4 gridOrigin[4];
    glm::ivec4 grid;
    glm::vec4 encode;
    glm::vec4 intensity;
    glm::ivec4 pixels; // x: resolution divisor, yz: G-buffer size
    glm::vec4 cameraPosition;
};

} // namespace

IndirectLookup::IndirectLookup(rhi::Device& device) : device_(device) {
    using namespace rhi;
    requireBindings(device, kLookupTextureBindings, "the indirect light's lookup");
    GraphicsPipelineDesc d = lookupDesc();
    const rhi::ShaderBinary* lookups[4] = {&shaders::lpv_lookup_1_frag, &shaders::lpv_lookup_2_frag,
                                           &shaders::lpv_lookup_3_frag, &shaders::lpv_lookup_4_frag};
    for (size_t c = 0; c < 4; ++c) {
        d.fragment = lookups[c];
        pipelines_[c] = device.createPipeline(d);
    }
    if (CascadeClasses::wanted(device)) {
        // Where a shader runs both sides of its branches: one draw per cascade class.
        d.debugName = "lpv lookup, one cascade class";
        const rhi::ShaderBinary* interior[4] = {
            &shaders::lpv_lookup_class0_frag, &shaders::lpv_lookup_class1_frag,
            &shaders::lpv_lookup_class2_frag, &shaders::lpv_lookup_class3_frag};
        const rhi::ShaderBinary* band[3] = {&shaders::lpv_lookup_class0_blend_frag,
                                            &shaders::lpv_lookup_class1_blend_frag,
                                            &shaders::lpv_lookup_class2_blend_frag};
        for (uint32_t c = 0; c < 4; ++c) {
            d.fragment = interior[c];
            CascadeClasses::configureLookupDraw(d, c, false);
            classPipelines_[c][0] = device.createPipeline(d);
            if (c == 3) continue;
            d.fragment = band[c];
            CascadeClasses::configureLookupDraw(d, c, true);
            classPipelines_[c][1] = device.createPipeline(d);
        }
    }
    pointSampler_ = device.createSampler({Filter::Nearest, Filter::Nearest, Filter::Nearest});
    SamplerDesc linear;
    linear.mipFilter = Filter::Nearest;
    linearSampler_ = device.createSampler(linear);
}

void IndirectLookup::enableGather() {
    using namespace rhi;
    if (gatherPipelines_[0]) return;
    requireBindings(device_, kGatherTextureBindings, "the indirect light's lookup with gi.gather");
    GraphicsPipelineDesc d = lookupDesc();
    d.debugName = "lpv lookup, gathered";
    const rhi::ShaderBinary* lookups[4] = {
        &shaders::lpv_lookup_1_gather_frag, &shaders::lpv_lookup_2_gather_frag,
        &shaders::lpv_lookup_3_gather_frag, &shaders::lpv_lookup_4_gather_frag};
    for (size_t c = 0; c < 4; ++c) {
        d.fragment = lookups[c];
        gatherPipelines_[c] = device_.createPipeline(d);
    }
    if (!classPipelines_[0][0]) return;
    d.debugName = "lpv lookup, one cascade class, gathered";
    const std::array shadersOf{
        std::array{&shaders::lpv_lookup_class0_gather_frag, &shaders::lpv_lookup_class0_blend_gather_frag},
        std::array{&shaders::lpv_lookup_class1_gather_frag, &shaders::lpv_lookup_class1_blend_gather_frag},
        std::array{&shaders::lpv_lookup_class2_gather_frag, &shaders::lpv_lookup_class2_blend_gather_frag}};
    static_assert(std::tuple_size_v<decltype(shadersOf)> == VplGather::kCascades,
                  "a gathered class variant per gathered cascade (gi/CMakeLists.txt builds them)");
    for (uint32_t c = 0; c < VplGather::kCascades; ++c)
        for (uint32_t band = 0; band < 2; ++band) {
            d.fragment = shadersOf[c][band];
            CascadeClasses::configureLookupDraw(d, c, band != 0);
            gatherClassPipelines_[c][band] = device_.createPipeline(d);
        }
}

IndirectLookup::~IndirectLookup() {
    for (rhi::GraphicsPipelineHandle p : pipelines_)
        device_.destroy(p);
    for (rhi::GraphicsPipelineHandle p : gatherPipelines_)
        if (p) device_.destroy(p);
    for (const auto& byBand : gatherClassPipelines_)
        for (rhi::GraphicsPipelineHandle p : byBand)
            if (p) device_.destroy(p);
    for (const auto& byBand : classPipelines_)
        for (rhi::GraphicsPipelineHandle p : byBand)
            if (p) device_.destroy(p);
    device_.destroy(pointSampler_);
    device_.destroy(linearSampler_);
}

void IndirectLookup::record(rhi::CommandList& cmd, const engine::CameraMatrices& camera,
                            const engine::GBufferView& gbuffer, std::span<const LookupCascade> cascades,
                            const LookupOptions& options, rhi::TextureHandle target,
                            rhi::TextureHandle glossyTarget, rhi::TextureHandle specularAlbedoTable,
                            const CascadeClasses* classes, const LookupGather* gather) {
    using namespace rhi;
    const uint32_t count = uint32_t(cascades.size());
    // Past the coarsest, a cascade's inputs are the coarsest's.
    const auto cascade = [&](uint32_t c) -> const LookupCascade& { return cascades[std::min(c, count - 1)]; };
    LookupUniforms u;
    u.invViewProjection = camera.invViewProjection;
    uint32_t keptToFaces = 0; // bit c: cascade c keeps to its faces
    for (uint32_t c = 0; c < 4; ++c) {
        u.gridOrigin[c] = glm::vec4(cascade(c).grid.origin, cascade(c).grid.cellSize);
        if (c < count && cascades[c].keptToFaces) keptToFaces |= 1u << c;
    }
    u.grid = glm::ivec4(int(cascades[0].grid.size), options.rgba8Range > 0.0f ? 1 : 0,
                        options.damping ? 1 : 0, int(count));
    u.encode = glm::vec4(options.rgba8Range, options.blendBand, float(keptToFaces), 0);
    // z: the glossy lobe's mean direction, or the cosine lobe around n.
    u.intensity = glm::vec4(options.intensity, 1.0f, options.glossyLobe ? 1.0f : 0.0f, 0);
    // w = 0: the first column of the camera matrix, read at an index lavapipe cannot fold.
    u.pixels = glm::ivec4(int(options.divisor), int(gbuffer.width), int(gbuffer.height), 0);
    u.cameraPosition = glm::vec4(camera.position, 1.0f);
    RenderPassDesc pass;
    // Classified, the sky's texels are drawn by no class: cleared to what the lookup writes there.
    const LoadOp load = classes ? LoadOp::Clear : LoadOp::DontCare;
    pass.colors[0] = {target, 0, 0, load};
    // The glossy radiance of the lobe's mean direction, which the march then draws over where it runs.
    pass.colors[1] = {glossyTarget, 0, 0, load};
    pass.colorCount = 2;
    if (classes) pass.depth = {classes->target(), 0, LoadOp::Load};
    pass.debugName = "lpv lookup";
    cmd.beginRenderPass(pass);
    std::array<std::array<rhi::TextureHandle, 3>, 4> volumes;
    for (uint32_t c = 0; c < count; ++c)
        volumes[c] = cascades[c].sh;
    const auto bindInputs = [&] {
        cmd.pushUniforms(0, &u, sizeof(u));
        bindCascadeReads(cmd, gbuffer, std::span(volumes.data(), count), pointSampler_, linearSampler_);
        cmd.bindTexture(15, gbuffer.albedo, pointSampler_);
        cmd.bindTexture(16, specularAlbedoTable, linearSampler_);
        // Without occlusion the bindings are unread; any 3D texture fills them.
        for (uint32_t c = 0; c < 4; ++c)
            cmd.bindTexture(17 + c, cascade(c).faces ? cascade(c).faces : volumes[0][0], pointSampler_);
        if (gather) {
            for (uint32_t c = 0; c < VplGather::kCascades; ++c)
                for (uint32_t ch = 0; ch < 3; ++ch)
                    cmd.bindTexture(21 + 3 * c + ch, gather->first[std::min(c, count - 1)][ch],
                                    linearSampler_);
            cmd.bindTexture(kGatherTextureBindings - 1, gather->gathered, pointSampler_);
        }
    };
    if (!classes) {
        cmd.bindPipeline(gather ? gatherPipelines_[count - 1] : pipelines_[count - 1]);
        bindInputs();
        cmd.draw(3);
    } else {
        for (uint32_t c = 0; c < count; ++c) {
            for (const bool blend : {false, true}) {
                if (blend && c + 1 == count) continue; // the coarsest has no band
                cmd.bindPipeline(gather && c < VplGather::kCascades ? gatherClassPipelines_[c][blend ? 1 : 0]
                                                                    : classPipelines_[c][blend ? 1 : 0]);
                bindInputs();
                cmd.draw(3);
            }
        }
    }
    cmd.endRenderPass();
}

} // namespace lpv::gi
