// OpenGL device: context start-up and capabilities, teardown, and the backend's factory entry.
#include "GlDevice.h"
#include "../src/DescValidation.h"

#include "../src/BackendFactory.h"
#include "../src/CpuRasterizer.h"
#include "platforms/Log.h"
#include "rhi/Error.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <string_view>

namespace lpv::rhi::gl {
namespace {

std::string glString(const Functions& gl, GLenum name) {
    const auto* s = reinterpret_cast<const char*>(gl.glGetString(name));
    return s ? s : "unknown";
}

uint32_t glInteger(const Functions& gl, GLenum name) {
    GLint v = 0;
    gl.glGetIntegerv(name, &v);
    return uint32_t(std::max(v, 0));
}

bool hasExtension(const Functions& gl, std::string_view name) {
    const GLint count = GLint(glInteger(gl, GL_NUM_EXTENSIONS));
    for (GLint i = 0; i < count; ++i) {
        const auto* e = reinterpret_cast<const char*>(gl.glGetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && name == e) return true;
    }
    return false;
}

} // namespace

GlDevice::GlDevice(const DeviceConfig& config, std::unique_ptr<platforms::GlContext> context)
    : config_(config), context_(std::move(context)), list_(*this) {
    const char* env = std::getenv("LPV_CONSERVATIVE_BARRIERS");
    conservativeBarriers_ = config.conservativeBarriers || (env && env[0] == '1');
    if (config.framesInFlight == 0) throw Error("DeviceConfig::framesInFlight must be at least 1");
    context_->makeCurrent();
    gl_.load(*context_); // throws BackendUnavailable naming a missing entry point
    const GLint major = GLint(glInteger(gl_, GL_MAJOR_VERSION)),
                minor = GLint(glInteger(gl_, GL_MINOR_VERSION));
    if (major * 10 + minor < 45)
        throw BackendUnavailable("OpenGL 4.5 core needed, " + std::string(context_->platformName()) +
                                 " gave " + std::to_string(major) + "." + std::to_string(minor));
    if (config_.validation) installDebugOutput(gl_, config_);
    label_.init(gl_);

    // Vulkan's conventions, set once: depth 0..1 and no y-flip (NDC y = -1 is memory row 0).
    gl_.glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    // Vulkan always encodes writes and clears of sRGB attachments; GL only with this enabled. It
    // changes nothing for linear targets. Presentation turns it off around its raw blit.
    gl_.glEnable(GL_FRAMEBUFFER_SRGB);
    gl_.glEnable(GL_PROGRAM_POINT_SIZE); // point sizes come from gl_PointSize, as in Vulkan
    gl_.glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    // Transfers use tightly packed rows.
    gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);

    caps_.deviceName = glString(gl_, GL_RENDERER);
    caps_.driverName = glString(gl_, GL_VERSION);
    caps_.timestampSource = GlTimestamps::sourceFor(caps_.deviceName);
    caps_.maxTimestampsPerFrame = config.maxTimestampsPerFrame;
    caps_.framesInFlight = config.framesInFlight;
    caps_.max3DTextureSize = glInteger(gl_, GL_MAX_3D_TEXTURE_SIZE);
    caps_.max2DTextureSize = glInteger(gl_, GL_MAX_TEXTURE_SIZE);
    caps_.maxColorTargets =
        std::min({glInteger(gl_, GL_MAX_DRAW_BUFFERS), glInteger(gl_, GL_MAX_COLOR_ATTACHMENTS),
                  RenderPassDesc::kMaxColorTargets});
    caps_.presentation = context_->hasDefaultFramebuffer();
    // SPIRV-Cross writes gl_Layer in a vertex shader under this extension.
    caps_.vertexShaderLayer =
        config.vertexShaderLayer && hasExtension(gl_, "GL_ARB_shader_viewport_layer_array");
    if (isCpuRasterizer(caps_.deviceName)) caps_.concurrentWorkgroups = cpuRasterizerThreads();
    caps_.maskedBranches = config.maskedBranches.value_or(isCpuRasterizer(caps_.deviceName));
    // SPIRV-Cross writes gl_FragStencilRefARB under this extension.
    caps_.shaderStencilExport = hasExtension(gl_, "GL_ARB_shader_stencil_export");
    caps_.multiDrawIndirect = config.multiDrawIndirect.value_or(true); // core since GL 4.3
    caps_.fragmentStores = true;                                       // core since GL 4.2
    // An image's binding is its image unit, and each stage counts its image uniforms.
    caps_.storageImageBindings = configuredStorageImageBindings(
        uint32_t(std::min({glInteger(gl_, GL_MAX_IMAGE_UNITS), glInteger(gl_, GL_MAX_COMPUTE_IMAGE_UNIFORMS),
                           glInteger(gl_, GL_MAX_FRAGMENT_IMAGE_UNIFORMS)})),
        config.storageImageBindings);
    // Capped at the bindings the command lists track, as storageImageBindings.
    caps_.fragmentTextureBindings =
        std::min({glInteger(gl_, GL_MAX_TEXTURE_IMAGE_UNITS),
                  config.fragmentTextureBindings.value_or(kMaxBindings), kMaxBindings});
    caps_.computeTextureBindings = std::min(glInteger(gl_, GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS), kMaxBindings);

    const uint64_t region = std::max(config.uniformRingBytes, 256u);
    uniformRing_.create(gl_, region, config.framesInFlight);
    label_(GL_BUFFER, uniformRing_.buffer(), "uniform ring");
    allocations_.add(ResourceType::Buffer, kUniformRingRecord,
                     {ResourceType::Buffer, "uniform ring", "rhi.internal", uniformRing_.totalBytes()});
    timestamps_.create(gl_, caps_.timestampSource, caps_.maxTimestampsPerFrame, config.framesInFlight + 1);
    framebuffers_.init(gl_, label_);
    fences_.assign(config.framesInFlight, nullptr);

    log::info("rhi: gl backend on '" + caps_.deviceName + "', OpenGL " + caps_.driverName + ", platform " +
              context_->platformName() + (config_.validation ? ", debug output on" : "") + ", timing " +
              std::string(timestampSourceName(caps_.timestampSource)));
}

GlDevice::~GlDevice() {
    try {
        context_->makeCurrent();
        releaseAll();
    } catch (const std::exception& e) {
        log::error(std::string("rhi: gl teardown: ") + e.what());
    }
}

void GlDevice::releaseAll() {
    gl_.glFinish();
    for (GLsync& f : fences_)
        if (f) gl_.glDeleteSync(f);
    fences_.clear();
    framebuffers_.destroy();
    if (presentFramebuffer_) gl_.glDeleteFramebuffers(1, &presentFramebuffer_);
    buffers.forEach([&](BufferHandle, GlBuffer& b) { gl_.glDeleteBuffers(1, &b.id); });
    textures.forEach([&](TextureHandle, GlTexture& t) { gl_.glDeleteTextures(1, &t.id); });
    samplers.forEach([&](SamplerHandle, GlSampler& s) { gl_.glDeleteSamplers(1, &s.id); });
    graphicsPipelines.forEach([&](GraphicsPipelineHandle, GlGraphicsPipeline& p) {
        gl_.glDeleteProgram(p.program);
        gl_.glDeleteVertexArrays(1, &p.vao);
    });
    computePipelines.forEach(
        [&](ComputePipelineHandle, GlComputePipeline& p) { gl_.glDeleteProgram(p.program); });
    timestamps_.destroy();
    uniformRing_.destroy();
    allocations_.remove(ResourceType::Buffer, kUniformRingRecord);
    if (config_.validation) uninstallDebugOutput(gl_);
    gl_.glFinish();
}

void GlDevice::waitIdle() {
    gl_.glFinish();
}

} // namespace lpv::rhi::gl

namespace lpv::rhi {

std::unique_ptr<Device> createGlDevice(const DeviceConfig& config) {
    std::unique_ptr<platforms::GlContext> context;
    try {
        if (config.window)
            context = platforms::createWindowGlContext(*config.window, config.validation);
        else if (config.glHeadless == GlHeadless::OSMesa)
            context = platforms::createOsMesaContext(config.validation);
        else
            context = platforms::createEglSurfacelessContext(config.validation);
    } catch (const BackendUnavailable&) {
        throw;
    } catch (const std::runtime_error& e) {
        throw BackendUnavailable(e.what());
    }
    return std::make_unique<gl::GlDevice>(config, std::move(context));
}

} // namespace lpv::rhi
