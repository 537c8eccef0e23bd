// OpenGL device: context, resources, transfers, frames and timestamps.
#include "GlDevice.h"

#include "GlFormats.h"

#include "../src/BackendFactory.h"
#include "platforms/Clock.h"
#include "platforms/Log.h"
#include "platforms/Window.h"
#include "rhi/Error.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace lpv::rhi::gl {
namespace {

void APIENTRY debugCallback(GLenum, GLenum type, GLuint, GLenum severity, GLsizei, const GLchar* message,
                            const void* user) {
    const auto* config = static_cast<const DeviceConfig*>(user);
    DebugMessage m;
    m.text = std::string("GL: ") + message;
    // Errors fail tests; undefined behaviour at high severity is a warning; the rest (performance
    // notes, shader recompiles, notifications) is information only.
    if (type == GL_DEBUG_TYPE_ERROR)
        m.severity = DebugSeverity::Error;
    else if (type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR && severity == GL_DEBUG_SEVERITY_HIGH)
        m.severity = DebugSeverity::Warning;
    else
        m.severity = DebugSeverity::Info;
    if (config->onDebugMessage)
        config->onDebugMessage(m);
    else if (m.severity != DebugSeverity::Info)
        log::warn(m.text);
}

} // namespace

GlDevice::GlDevice(const DeviceConfig& config, std::unique_ptr<platforms::GlContext> context)
    : config_(config), context_(std::move(context)), list_(*this) {
    gl_.load(*context_);
    const char* renderer = reinterpret_cast<const char*>(gl_.glGetString(GL_RENDERER));
    const char* version = reinterpret_cast<const char*>(gl_.glGetString(GL_VERSION));
    GLint major = 0, minor = 0;
    gl_.glGetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
        throw BackendUnavailable("OpenGL 4.5 needed, the context has " + std::to_string(major) + "." +
                                 std::to_string(minor));
    if (config_.validation) {
        gl_.glEnable(GL_DEBUG_OUTPUT);
        gl_.glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        gl_.glDebugMessageCallback(debugCallback, &config_);
        gl_.glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    }
    // Vulkan's conventions: depth 0..1; NDC y = -1 is memory row 0 on both APIs already.
    gl_.glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gl_.glEnable(GL_FRAMEBUFFER_SRGB); // sRGB targets encode on write, as Vulkan's do
    gl_.glEnable(GL_PROGRAM_POINT_SIZE);
    gl_.glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);

    caps_.deviceName = renderer ? renderer : "unknown";
    caps_.driverName = version ? version : "unknown";
    const bool softwareTimers = caps_.deviceName.find("llvmpipe") != std::string::npos ||
                                caps_.deviceName.find("softpipe") != std::string::npos;
    caps_.timestampSource = softwareTimers ? TimestampSource::CpuFinished : TimestampSource::GpuQueries;
    caps_.maxTimestampsPerFrame = config.maxTimestampsPerFrame;
    caps_.framesInFlight = std::max(1u, config.framesInFlight);
    GLint v = 0;
    gl_.glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &v);
    caps_.max3DTextureSize = uint32_t(v);
    gl_.glGetIntegerv(GL_MAX_TEXTURE_SIZE, &v);
    caps_.max2DTextureSize = uint32_t(v);
    gl_.glGetIntegerv(GL_MAX_DRAW_BUFFERS, &v);
    caps_.maxColorTargets = uint32_t(std::min<GLint>(v, RenderPassDesc::kMaxColorTargets));
    caps_.presentation = context_->hasDefaultFramebuffer();
    gl_.glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &v);
    uniformAlignment_ = uint64_t(std::max(v, 16));

    gl_.glCreateBuffers(1, &uniformRing_);
    gl_.glNamedBufferStorage(uniformRing_, config.uniformRingBytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    label(GL_BUFFER, uniformRing_, "uniform ring");
    allocations_.add(ResourceType::Buffer, 0xfffffffeu,
                     {ResourceType::Buffer, "uniform ring", "rhi.internal", config.uniformRingBytes});

    slots_.resize(caps_.framesInFlight + 1);
    for (FrameSlot& s : slots_) {
        s.cpuTimes.assign(caps_.maxTimestampsPerFrame, 0);
        s.written.assign(caps_.maxTimestampsPerFrame, false);
        if (caps_.timestampSource == TimestampSource::GpuQueries) {
            s.queries.resize(caps_.maxTimestampsPerFrame);
            gl_.glCreateQueries(GL_TIMESTAMP, GLsizei(s.queries.size()), s.queries.data());
        }
    }
    fboKey_.reserve(2 * (RenderPassDesc::kMaxColorTargets + 1));
    log::info(std::string("rhi: gl backend on '") + caps_.deviceName + "', OpenGL " + caps_.driverName +
              " via " + context_->platformName() + (config_.validation ? ", debug output on" : "") +
              ", timing " + std::string(timestampSourceName(caps_.timestampSource)));
}

GlDevice::~GlDevice() {
    context_->makeCurrent();
    gl_.glFinish();
    for (auto& [key, fbo] : framebuffers_)
        gl_.glDeleteFramebuffers(1, &fbo);
    if (presentFbo_) gl_.glDeleteFramebuffers(1, &presentFbo_);
    buffers.forEach([&](BufferHandle, GlBuffer& b) { gl_.glDeleteBuffers(1, &b.id); });
    textures.forEach([&](TextureHandle, GlTexture& t) { gl_.glDeleteTextures(1, &t.id); });
    samplers.forEach([&](SamplerHandle, GlSampler& s) { gl_.glDeleteSamplers(1, &s.id); });
    graphicsPipelines.forEach([&](GraphicsPipelineHandle, GlGraphicsPipeline& p) {
        gl_.glDeleteProgram(p.program);
        gl_.glDeleteVertexArrays(1, &p.vao);
    });
    computePipelines.forEach(
        [&](ComputePipelineHandle, GlComputePipeline& p) { gl_.glDeleteProgram(p.program); });
    for (FrameSlot& s : slots_) {
        if (s.fence) gl_.glDeleteSync(s.fence);
        if (!s.queries.empty()) gl_.glDeleteQueries(GLsizei(s.queries.size()), s.queries.data());
    }
    gl_.glDeleteBuffers(1, &uniformRing_);
    if (config_.validation) gl_.glDebugMessageCallback(nullptr, nullptr);
}

void GlDevice::label(GLenum type, GLuint id, const std::string& name) const {
    if (!name.empty()) gl_.glObjectLabel(type, id, GLsizei(name.size()), name.c_str());
}

void GlDevice::requireOutsideFrame(const char* what) const {
    if (inFrame_)
        throw Error(std::string(what) +
                    " inside a frame: immediate transfers wait for the GPU and must run between frames");
}

BufferHandle GlDevice::createBuffer(const BufferDesc& desc, const void* initialData) {
    if (desc.size == 0) throw Error("buffer '" + desc.debugName + "': size is 0");
    GlBuffer b;
    b.desc = desc;
    gl_.glCreateBuffers(1, &b.id);
    GLbitfield flags = GL_DYNAMIC_STORAGE_BIT;
    if (desc.access == MemoryAccess::HostWrite)
        flags |= GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    gl_.glNamedBufferStorage(b.id, GLsizeiptr(desc.size), initialData, flags);
    if (desc.access == MemoryAccess::HostWrite)
        b.mapped = gl_.glMapNamedBufferRange(b.id, 0, GLsizeiptr(desc.size),
                                             GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT);
    label(GL_BUFFER, b.id, desc.debugName);
    const BufferHandle h = buffers.insert(std::move(b));
    allocations_.add(ResourceType::Buffer, h.bits,
                     {ResourceType::Buffer, desc.debugName, desc.category, desc.size});
    return h;
}

TextureHandle GlDevice::createTexture(const TextureDesc& desc) {
    if (desc.width == 0 || desc.height == 0 || desc.depthOrLayers == 0 || desc.mipLevels == 0)
        throw Error("texture '" + desc.debugName + "': zero extent or mip count");
    const GlFormat f = glFormat(desc.format);
    GlTexture t;
    t.desc = desc;
    t.target = textureTarget(desc.kind);
    gl_.glCreateTextures(t.target, 1, &t.id);
    if (desc.kind == TextureKind::Tex2D)
        gl_.glTextureStorage2D(t.id, GLsizei(desc.mipLevels), f.internal, GLsizei(desc.width),
                               GLsizei(desc.height));
    else
        gl_.glTextureStorage3D(t.id, GLsizei(desc.mipLevels), f.internal, GLsizei(desc.width),
                               GLsizei(desc.height), GLsizei(desc.depthOrLayers));
    gl_.glTextureParameteri(t.id, GL_TEXTURE_MAX_LEVEL, GLint(desc.mipLevels - 1));
    label(GL_TEXTURE, t.id, desc.debugName);
    const TextureHandle h = textures.insert(std::move(t));
    allocations_.add(ResourceType::Texture, h.bits,
                     {ResourceType::Texture, desc.debugName, desc.category, textureBytes(desc)});
    return h;
}

SamplerHandle GlDevice::createSampler(const SamplerDesc& d) {
    GlSampler s;
    gl_.glCreateSamplers(1, &s.id);
    const bool mips = true;
    GLenum minFilter = d.minFilter == Filter::Linear ? GL_LINEAR : GL_NEAREST;
    if (mips) {
        if (d.minFilter == Filter::Linear)
            minFilter = d.mipFilter == Filter::Linear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST;
        else
            minFilter = d.mipFilter == Filter::Linear ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST;
    }
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_MIN_FILTER, GLint(minFilter));
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_MAG_FILTER,
                            d.magFilter == Filter::Linear ? GL_LINEAR : GL_NEAREST);
    const GLint wrap = GLint(addressMode(d.address));
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_WRAP_S, wrap);
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_WRAP_T, wrap);
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_WRAP_R, wrap);
    const float white[4] = {1, 1, 1, 1};
    gl_.glSamplerParameterfv(s.id, GL_TEXTURE_BORDER_COLOR, white);
    if (d.maxAnisotropy > 1.0f) gl_.glSamplerParameterf(s.id, GL_TEXTURE_MAX_ANISOTROPY, d.maxAnisotropy);
    if (d.compareEnable) {
        gl_.glSamplerParameteri(s.id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        gl_.glSamplerParameteri(s.id, GL_TEXTURE_COMPARE_FUNC, GLint(compareFunc(d.compareOp)));
    }
    label(GL_SAMPLER, s.id, d.debugName);
    return samplers.insert(s);
}

GLuint GlDevice::linkProgram(std::initializer_list<const ShaderBinary*> stages, const std::string& name) {
    const GLuint program = gl_.glCreateProgram();
    std::vector<GLuint> shaders;
    for (const ShaderBinary* s : stages) {
        const GLenum type = s->stage == ShaderStage::Vertex     ? GL_VERTEX_SHADER
                            : s->stage == ShaderStage::Fragment ? GL_FRAGMENT_SHADER
                                                                : GL_COMPUTE_SHADER;
        const GLuint shader = gl_.glCreateShader(type);
        const GLchar* source = s->glsl.data();
        const GLint length = GLint(s->glsl.size());
        gl_.glShaderSource(shader, 1, &source, &length);
        gl_.glCompileShader(shader);
        GLint ok = 0;
        gl_.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[4096] = {};
            gl_.glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
            gl_.glDeleteShader(shader);
            gl_.glDeleteProgram(program);
            throw Error("OpenGL: shader " + std::string(s->name) + " (pipeline '" + name +
                        "') does not compile: " + log);
        }
        gl_.glAttachShader(program, shader);
        shaders.push_back(shader);
    }
    gl_.glLinkProgram(program);
    for (GLuint s : shaders)
        gl_.glDeleteShader(s);
    GLint ok = 0;
    gl_.glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        gl_.glGetProgramInfoLog(program, sizeof(log), nullptr, log);
        gl_.glDeleteProgram(program);
        throw Error("OpenGL: pipeline '" + name + "' does not link: " + log);
    }
    label(GL_PROGRAM, program, name);
    return program;
}

GraphicsPipelineHandle GlDevice::createPipeline(const GraphicsPipelineDesc& desc) {
    if (!desc.vertex) throw Error("graphics pipeline '" + desc.debugName + "': no vertex shader");
    GlGraphicsPipeline p;
    p.desc = desc;
    p.program = desc.fragment ? linkProgram({desc.vertex, desc.fragment}, desc.debugName)
                              : linkProgram({desc.vertex}, desc.debugName);
    p.baseInstanceLocation = gl_.glGetUniformLocation(p.program, "SPIRV_Cross_BaseInstance");
    gl_.glCreateVertexArrays(1, &p.vao);
    for (const VertexAttribute& a : desc.attributes) {
        const GlVertexFormat f = vertexFormat(a.format);
        gl_.glEnableVertexArrayAttrib(p.vao, a.location);
        gl_.glVertexArrayAttribFormat(p.vao, a.location, f.size, f.type, f.normalized, a.offset);
        gl_.glVertexArrayAttribBinding(p.vao, a.location, a.bufferSlot);
    }
    for (size_t i = 0; i < desc.vertexBuffers.size(); ++i)
        gl_.glVertexArrayBindingDivisor(p.vao, GLuint(i), desc.vertexBuffers[i].perInstance ? 1 : 0);
    label(GL_VERTEX_ARRAY, p.vao, desc.debugName);
    return graphicsPipelines.insert(std::move(p));
}

ComputePipelineHandle GlDevice::createPipeline(const ComputePipelineDesc& desc) {
    if (!desc.compute) throw Error("compute pipeline '" + desc.debugName + "': no compute shader");
    return computePipelines.insert({linkProgram({desc.compute}, desc.debugName)});
}

void GlDevice::destroy(BufferHandle h) {
    GlBuffer b = buffers.remove(h);
    gl_.glDeleteBuffers(1, &b.id);
    allocations_.remove(ResourceType::Buffer, h.bits);
}

void GlDevice::destroy(TextureHandle h) {
    GlTexture t = textures.remove(h);
    for (auto it = framebuffers_.begin(); it != framebuffers_.end();) {
        const bool uses = std::find(it->first.begin(), it->first.end(), uint64_t(t.id)) != it->first.end();
        if (uses) {
            gl_.glDeleteFramebuffers(1, &it->second);
            it = framebuffers_.erase(it);
        } else {
            ++it;
        }
    }
    gl_.glDeleteTextures(1, &t.id);
    allocations_.remove(ResourceType::Texture, h.bits);
}

void GlDevice::destroy(SamplerHandle h) {
    GlSampler s = samplers.remove(h);
    gl_.glDeleteSamplers(1, &s.id);
}

void GlDevice::destroy(GraphicsPipelineHandle h) {
    GlGraphicsPipeline p = graphicsPipelines.remove(h);
    gl_.glDeleteProgram(p.program);
    gl_.glDeleteVertexArrays(1, &p.vao);
}

void GlDevice::destroy(ComputePipelineHandle h) {
    GlComputePipeline p = computePipelines.remove(h);
    gl_.glDeleteProgram(p.program);
}

uint64_t GlDevice::mipBytes(const TextureDesc& d, uint32_t mip) {
    const uint64_t w = std::max(1u, d.width >> mip), h = std::max(1u, d.height >> mip);
    const uint64_t z = d.kind == TextureKind::Tex3D ? std::max(1u, d.depthOrLayers >> mip) : d.depthOrLayers;
    return w * h * z * bytesPerPixel(d.format);
}

void GlDevice::uploadBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) {
    requireOutsideFrame("uploadBuffer");
    const GlBuffer& b = buffers.get(h);
    if (offset + size > b.desc.size)
        throw Error("uploadBuffer: range exceeds buffer '" + b.desc.debugName + "'");
    gl_.glNamedBufferSubData(b.id, GLintptr(offset), GLsizeiptr(size), data);
}

void GlDevice::uploadTexture(TextureHandle h, uint32_t mip, const void* data, uint64_t size) {
    requireOutsideFrame("uploadTexture");
    const GlTexture& t = textures.get(h);
    if (mip >= t.desc.mipLevels || size != mipBytes(t.desc, mip))
        throw Error("uploadTexture '" + t.desc.debugName + "': mip " + std::to_string(mip) + " needs " +
                    std::to_string(mip < t.desc.mipLevels ? mipBytes(t.desc, mip) : 0) + " bytes, got " +
                    std::to_string(size));
    const GlFormat f = glFormat(t.desc.format);
    const GLsizei w = GLsizei(std::max(1u, t.desc.width >> mip)),
                  hh = GLsizei(std::max(1u, t.desc.height >> mip));
    if (t.desc.kind == TextureKind::Tex2D) {
        gl_.glTextureSubImage2D(t.id, GLint(mip), 0, 0, w, hh, f.format, f.type, data);
    } else {
        const GLsizei z =
            GLsizei(t.desc.kind == TextureKind::Tex3D ? std::max(1u, t.desc.depthOrLayers >> mip)
                                                      : t.desc.depthOrLayers);
        gl_.glTextureSubImage3D(t.id, GLint(mip), 0, 0, 0, w, hh, z, f.format, f.type, data);
    }
}

void GlDevice::readBuffer(BufferHandle h, uint64_t offset, void* out, uint64_t size) {
    requireOutsideFrame("readBuffer");
    const GlBuffer& b = buffers.get(h);
    if (offset + size > b.desc.size)
        throw Error("readBuffer: range exceeds buffer '" + b.desc.debugName + "'");
    gl_.glGetNamedBufferSubData(b.id, GLintptr(offset), GLsizeiptr(size), out);
}

void GlDevice::readTexture(TextureHandle h, uint32_t mip, void* out, uint64_t size) {
    requireOutsideFrame("readTexture");
    const GlTexture& t = textures.get(h);
    if (mip >= t.desc.mipLevels || size != mipBytes(t.desc, mip))
        throw Error("readTexture '" + t.desc.debugName + "': mip " + std::to_string(mip) + " needs " +
                    std::to_string(mip < t.desc.mipLevels ? mipBytes(t.desc, mip) : 0) + " bytes, got " +
                    std::to_string(size));
    const GlFormat f = glFormat(t.desc.format);
    gl_.glGetTextureImage(t.id, GLint(mip), f.format, f.type, GLsizei(size), out);
}

void* GlDevice::mapped(BufferHandle h) {
    GlBuffer& b = buffers.get(h);
    if (!b.mapped) throw Error("buffer '" + b.desc.debugName + "' is not MemoryAccess::HostWrite");
    return b.mapped;
}

GLuint GlDevice::framebufferFor(const RenderPassDesc& desc) {
    // Key: per attachment (texture name, mip << 32 | layer).
    fboKey_.clear();
    for (uint32_t i = 0; i < desc.colorCount; ++i) {
        const GlTexture& t = textures.get(desc.colors[i].texture);
        fboKey_.push_back(t.id);
        fboKey_.push_back((uint64_t(desc.colors[i].mipLevel) << 32) | desc.colors[i].layer);
    }
    if (desc.depth.texture) {
        fboKey_.push_back(textures.get(desc.depth.texture).id);
        fboKey_.push_back((uint64_t(1) << 63) | desc.depth.layer);
    }
    if (auto it = framebuffers_.find(fboKey_); it != framebuffers_.end()) return it->second;
    GLuint fbo = 0;
    gl_.glCreateFramebuffers(1, &fbo);
    GLenum drawBuffers[RenderPassDesc::kMaxColorTargets];
    for (uint32_t i = 0; i < desc.colorCount; ++i) {
        const ColorAttachment& c = desc.colors[i];
        const GlTexture& t = textures.get(c.texture);
        if (t.desc.kind == TextureKind::Tex2D)
            gl_.glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, t.id, GLint(c.mipLevel));
        else
            gl_.glNamedFramebufferTextureLayer(fbo, GL_COLOR_ATTACHMENT0 + i, t.id, GLint(c.mipLevel),
                                               GLint(c.layer));
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    if (desc.depth.texture) {
        const GlTexture& t = textures.get(desc.depth.texture);
        if (t.desc.kind == TextureKind::Tex2D)
            gl_.glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, t.id, 0);
        else
            gl_.glNamedFramebufferTextureLayer(fbo, GL_DEPTH_ATTACHMENT, t.id, 0, GLint(desc.depth.layer));
    }
    gl_.glNamedFramebufferDrawBuffers(fbo, GLsizei(desc.colorCount), drawBuffers);
    const GLenum status = gl_.glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        gl_.glDeleteFramebuffers(1, &fbo);
        throw Error(std::string("OpenGL: render pass '") + desc.debugName +
                    "' has an incomplete framebuffer (0x" + std::to_string(status) + ")");
    }
    label(GL_FRAMEBUFFER, fbo, desc.debugName);
    framebuffers_.emplace(fboKey_, fbo);
    return fbo;
}

uint64_t GlDevice::allocateUniforms(const void* data, uint32_t size) {
    const uint64_t offset = (uniformHead_ + uniformAlignment_ - 1) / uniformAlignment_ * uniformAlignment_;
    if (offset + size > config_.uniformRingBytes)
        throw Error("pushUniforms: more than uniformRingBytes (" + std::to_string(config_.uniformRingBytes) +
                    ") in one frame");
    // Buffer updates are ordered with the draws that read them, so rewriting the ring from the
    // start each frame is safe; the driver keeps in-flight data alive.
    gl_.glNamedBufferSubData(uniformRing_, GLintptr(offset), size, data);
    uniformHead_ = offset + size;
    return offset;
}

void GlDevice::recordTimestamp(uint32_t index) {
    if (!inFrame_) throw Error("writeTimestamp outside a frame");
    if (index >= caps_.maxTimestampsPerFrame)
        throw Error("timestamp slot " + std::to_string(index) + " >= maxTimestampsPerFrame " +
                    std::to_string(caps_.maxTimestampsPerFrame));
    FrameSlot& s = slot(frame_);
    if (caps_.timestampSource == TimestampSource::CpuFinished) {
        gl_.glFinish();
        s.cpuTimes[index] = platforms::nowNanoseconds();
    } else {
        gl_.glQueryCounter(s.queries[index], GL_TIMESTAMP);
    }
    s.written[index] = true;
}

CommandList& GlDevice::beginFrame() {
    if (inFrame_) throw Error("beginFrame() called twice without endFrame()");
    ++frame_;
    FrameSlot& s = slot(frame_);
    // Bound the CPU's lead: wait for the frame that last used this slot.
    if (s.fence) {
        gl_.glClientWaitSync(s.fence, GL_SYNC_FLUSH_COMMANDS_BIT, ~GLuint64(0));
        gl_.glDeleteSync(s.fence);
        s.fence = nullptr;
    }
    s.frame = frame_;
    s.complete = false;
    std::fill(s.written.begin(), s.written.end(), false);
    std::fill(s.cpuTimes.begin(), s.cpuTimes.end(), 0);
    uniformHead_ = 0;
    inFrame_ = true;
    list_.reset();
    return list_;
}

void GlDevice::endFrame(TextureHandle present) {
    if (!inFrame_) throw Error("endFrame() without beginFrame()");
    if (present && context_->hasDefaultFramebuffer()) {
        const GlTexture& t = textures.get(present);
        if (!presentFbo_) gl_.glCreateFramebuffers(1, &presentFbo_);
        gl_.glNamedFramebufferTexture(presentFbo_, GL_COLOR_ATTACHMENT0, t.id, 0);
        gl_.glNamedFramebufferReadBuffer(presentFbo_, GL_COLOR_ATTACHMENT0);
        GLint viewport[4] = {};
        uint32_t w = t.desc.width, h = t.desc.height;
        if (config_.window) config_.window->framebufferSize(w, h);
        (void)viewport;
        // A plain copy of the stored bytes (no sRGB conversion), flipped so row 0 is at the top.
        gl_.glDisable(GL_FRAMEBUFFER_SRGB);
        gl_.glDisable(GL_SCISSOR_TEST);
        gl_.glBlitNamedFramebuffer(presentFbo_, 0, 0, 0, GLint(t.desc.width), GLint(t.desc.height), 0,
                                   GLint(h), GLint(w), 0, GL_COLOR_BUFFER_BIT, GL_LINEAR);
        gl_.glEnable(GL_FRAMEBUFFER_SRGB);
        context_->swapBuffers();
    } else if (present) {
        textures.get(present);
    }
    FrameSlot& s = slot(frame_);
    s.fence = gl_.glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl_.glFlush();
    s.complete = true;
    inFrame_ = false;
}

bool GlDevice::readTimestamps(uint64_t frame, std::span<uint64_t> out) {
    FrameSlot& s = slot(frame);
    if (s.frame != frame || !s.complete || caps_.timestampSource == TimestampSource::None) return false;
    if (out.size() > caps_.maxTimestampsPerFrame)
        throw Error("readTimestamps: more slots than maxTimestampsPerFrame");
    if (caps_.timestampSource == TimestampSource::CpuFinished) {
        for (size_t i = 0; i < out.size(); ++i)
            out[i] = s.written[i] ? s.cpuTimes[i] : 0;
        return true;
    }
    for (size_t i = 0; i < out.size(); ++i) {
        if (!s.written[i]) continue;
        GLint available = 0;
        gl_.glGetQueryObjectiv(s.queries[i], GL_QUERY_RESULT_AVAILABLE, &available);
        if (!available) return false;
    }
    for (size_t i = 0; i < out.size(); ++i) {
        GLuint64 v = 0;
        if (s.written[i]) gl_.glGetQueryObjectui64v(s.queries[i], GL_QUERY_RESULT, &v);
        out[i] = v;
    }
    return true;
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
    } catch (const std::runtime_error& e) {
        throw BackendUnavailable(e.what());
    }
    return std::make_unique<gl::GlDevice>(config, std::move(context));
}

} // namespace lpv::rhi
