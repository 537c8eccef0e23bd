// Commands of the GL backend, run on the context as they are recorded (see GlCommandList.h).
// Argument checks mirror the Vulkan backend's so misuse fails the same way on both.
#include "GlCommandList.h"
#include "../src/DescValidation.h"

#include "GlDevice.h"
#include "GlFormats.h"

#include "rhi/Error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace lpv::rhi::gl {
namespace {

// Vulkan encodes the (linear) clear value of an sRGB image; glClearTexImage copies it unconverted.
float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

GLuint clearUint(float v) {
    return GLuint(std::max(0.0f, v));
}

// The barrier bit that orders a shader's access through a binding of this kind after earlier
// shader stores.
GLbitfield accessBit(BindingKind kind) {
    switch (kind) {
    case BindingKind::UniformBuffer:
        return GL_UNIFORM_BARRIER_BIT;
    case BindingKind::StorageBuffer:
        return GL_SHADER_STORAGE_BARRIER_BIT;
    case BindingKind::Texture:
        return GL_TEXTURE_FETCH_BARRIER_BIT;
    case BindingKind::StorageImage:
        return GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    }
    return GL_ALL_BARRIER_BITS;
}

} // namespace

void GlCommandList::begin() {
    resetCounts();
    inPass_ = false;
    markerDepth_ = 0;
    graphics_ = {};
    compute_ = {};
    activeProgram_ = 0;
    device_.gl().glUseProgram(0);
    vertexBuffers_ = {};
    indexBuffer_ = 0;
    indexOffset_ = 0;
    bound_ = {};
}

bool GlCommandList::finish() {
    if (inPass_) throw Error("endFrame() inside a render pass: call endRenderPass() first");
    for (; markerDepth_ > 0; --markerDepth_)
        device_.gl().glPopDebugGroup();
    if (hazards_.empty()) return false;
    barrier(GL_ALL_BARRIER_BITS);
    return true;
}

void GlCommandList::barrier(GLbitfield bits) {
    if (!bits) return;
    device_.gl().glMemoryBarrier(bits);
    ++counts_.barriers;
    hazards_.paid(bits);
}

void GlCommandList::conservativeBarrier() {
    if (device_.conservativeBarriers()) barrier(GL_ALL_BARRIER_BITS);
}

GLbitfield GlCommandList::shaderHazards(const std::vector<ShaderBinding>& bindings) const {
    GLbitfield bits = 0;
    for (const ShaderBinding& b : bindings) {
        const uint64_t key = bound_[b.binding];
        bits |= b.writable ? hazards_.beforeShaderWrite(key, accessBit(b.kind))
                           : hazards_.beforeRead(key, accessBit(b.kind));
    }
    return bits;
}

void GlCommandList::noteShaderAccesses(const std::vector<ShaderBinding>& bindings) {
    for (const ShaderBinding& b : bindings) {
        const uint64_t key = bound_[b.binding];
        const bool incoherent = b.kind == BindingKind::StorageImage || b.kind == BindingKind::StorageBuffer;
        const auto note = [&] {
            return b.writable ? hazards_.noteWrite(key) : hazards_.noteRead(key, incoherent);
        };
        if (note()) continue;
        barrier(GL_ALL_BARRIER_BITS); // too many to track: pay now, start over
        note();
    }
}

void GlCommandList::requireFrame(const char* what) const {
    if (!device_.inFrame()) throw Error(std::string(what) + " outside beginFrame()/endFrame()");
}

void GlCommandList::requirePass(bool inside, const char* what) const {
    requireFrame(what);
    if (inPass_ != inside)
        throw Error(std::string(what) + (inside ? " outside a render pass" : " inside a render pass"));
}

void GlCommandList::checkBinding(uint32_t binding, const char* what) const {
    requireFrame(what);
    if (binding >= kMaxBindings)
        throw Error(std::string(what) + ": binding " + std::to_string(binding) +
                    " >= " + std::to_string(kMaxBindings));
}

void GlCommandList::useProgram(GLuint program) {
    if (activeProgram_ == program) return;
    device_.gl().glUseProgram(program);
    activeProgram_ = program;
}

void GlCommandList::restoreWriteMasks() {
    const bool bound = graphics_ && device_.graphicsPipelines.contains(graphics_);
    const GraphicsPipelineDesc* d = bound ? &device_.graphicsPipelines.get(graphics_).desc : nullptr;
    device_.gl().glDepthMask(d && d->depthWrite ? GL_TRUE : GL_FALSE);
    device_.gl().glStencilMask(d && d->stencil.enabled ? d->stencil.writeMask : 0u);
}

void GlCommandList::beginRenderPass(const RenderPassDesc& desc) {
    requirePass(false, "beginRenderPass");
    if (desc.colorCount > RenderPassDesc::kMaxColorTargets)
        throw Error("beginRenderPass: more than 8 color targets");
    if (desc.colorCount == 0 && !desc.depth.texture) throw Error("beginRenderPass: no color or depth target");

    GlAttachment colors[RenderPassDesc::kMaxColorTargets];
    GlAttachment depth;
    uint32_t width = 0, height = 0;
    bool first = true;
    const bool layered = isLayeredPass(desc, device_.caps());
    uint32_t layerCount = 1;
    auto checkExtent = [&](const GlTexture& t, uint32_t mip) {
        if (first) {
            width = t.width(mip);
            height = t.height(mip);
            first = false;
        } else if (t.width(mip) < width || t.height(mip) < height) {
            throw Error("beginRenderPass '" + std::string(desc.debugName) + "': target '" + t.desc.debugName +
                        "' is smaller than the first target");
        }
    };
    for (uint32_t i = 0; i < desc.colorCount; ++i) {
        const ColorAttachment& a = desc.colors[i];
        const GlTexture& t = device_.textures.get(a.texture);
        if (!(t.desc.usage & kTextureColorTarget) || isDepthFormat(t.desc.format))
            throw Error("beginRenderPass: texture '" + t.desc.debugName + "' is not a color target");
        if (a.mipLevel >= t.desc.mipLevels || a.layer >= t.depthOrLayers(a.mipLevel))
            throw Error("beginRenderPass: texture '" + t.desc.debugName + "' has no mip " +
                        std::to_string(a.mipLevel) + " layer " + std::to_string(a.layer));
        checkExtent(t, a.mipLevel);
        if (layered)
            layerCount = layeredTargetLayers(desc, i, t.desc, t.depthOrLayers(a.mipLevel), layerCount);
        colors[i] = {t.id, !layered && t.desc.kind != TextureKind::Tex2D, a.mipLevel, a.layer};
    }
    if (desc.depth.texture) {
        const GlTexture& t = device_.textures.get(desc.depth.texture);
        if (!isDepthFormat(t.desc.format) || !(t.desc.usage & (kTextureDepthTarget | kTextureColorTarget)))
            throw Error("beginRenderPass: texture '" + t.desc.debugName + "' is not a depth target");
        if (desc.depth.layer >= t.depthOrLayers(0))
            throw Error("beginRenderPass: depth texture '" + t.desc.debugName + "' has no layer " +
                        std::to_string(desc.depth.layer));
        checkExtent(t, 0);
        depth = {t.id, t.desc.kind != TextureKind::Tex2D, 0, desc.depth.layer, hasStencil(t.desc.format)};
    }

    // The targets are written (and loaded) through the framebuffer: after earlier shader stores to
    // them, or image loads of them, a barrier first.
    GLbitfield bits = 0;
    for (uint32_t i = 0; i < desc.colorCount; ++i)
        bits |=
            hazards_.beforeCommandWrite(GlHazards::textureKey(colors[i].texture), GL_FRAMEBUFFER_BARRIER_BIT);
    if (desc.depth.texture)
        bits |= hazards_.beforeCommandWrite(GlHazards::textureKey(depth.texture), GL_FRAMEBUFFER_BARRIER_BIT);
    barrier(bits);
    const Functions& gl = device_.gl();
    const GLuint fbo = device_.framebuffers().get(colors, desc.colorCount,
                                                  desc.depth.texture ? &depth : nullptr, desc.debugName);
    gl.glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, desc.debugName);
    gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    // The RHI's rule: viewport and scissor start as the whole first target. Set them before the
    // clears, which obey the scissor.
    setViewport({0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f});
    gl.glEnable(GL_SCISSOR_TEST);
    gl.glScissor(0, 0, GLsizei(width), GLsizei(height));
    for (uint32_t i = 0; i < desc.colorCount; ++i) {
        const ColorAttachment& a = desc.colors[i];
        if (a.load != LoadOp::Clear) continue; // Load keeps the contents; DontCare may too
        if (isIntegerFormat(device_.textures.get(a.texture).desc.format)) {
            const GLuint v[4] = {clearUint(a.clearColor[0]), clearUint(a.clearColor[1]),
                                 clearUint(a.clearColor[2]), clearUint(a.clearColor[3])};
            gl.glClearNamedFramebufferuiv(fbo, GL_COLOR, GLint(i), v);
        } else {
            // With GL_FRAMEBUFFER_SRGB on, an sRGB target gets the encoded value, as in Vulkan.
            gl.glClearNamedFramebufferfv(fbo, GL_COLOR, GLint(i), a.clearColor.data());
        }
    }
    if (desc.depth.texture && desc.depth.load == LoadOp::Clear) {
        gl.glDepthMask(GL_TRUE); // clears obey the write masks
        if (depth.stencil) {
            gl.glStencilMask(0xff);
            gl.glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, desc.depth.clearDepth,
                                         GLint(desc.depth.clearStencil));
        } else {
            gl.glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &desc.depth.clearDepth);
        }
        restoreWriteMasks();
    }
    inPass_ = true;
}

void GlCommandList::endRenderPass() {
    requirePass(true, "endRenderPass");
    const Functions& gl = device_.gl();
    gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl.glPopDebugGroup();
    // Storage writes of the pass's shaders were noted draw by draw; the conservative rule makes
    // them visible to everything recorded later.
    inPass_ = false;
    conservativeBarrier();
}

void GlCommandList::setViewport(const Viewport& vp) {
    requireFrame("setViewport");
    // No y-flip: with GL_LOWER_LEFT, NDC y = -1 lands on window row 0, which is memory row 0.
    device_.gl().glViewportIndexedf(0, vp.x, vp.y, vp.width, vp.height);
    device_.gl().glDepthRangef(vp.minDepth, vp.maxDepth);
}

void GlCommandList::setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) {
    requireFrame("setScissor");
    // Clipped at the origin like the Vulkan backend's (which must: Vulkan rejects negative offsets).
    clipScissorToOrigin(x, y, width, height);
    device_.gl().glScissor(x, y, GLsizei(std::min<uint32_t>(width, 0x7fffffffu)),
                           GLsizei(std::min<uint32_t>(height, 0x7fffffffu)));
}

void GlCommandList::bindPipeline(GraphicsPipelineHandle h) {
    requireFrame("bindPipeline");
    const GlGraphicsPipeline& p = device_.graphicsPipelines.get(h);
    const GraphicsPipelineDesc& d = p.desc;
    const Functions& gl = device_.gl();
    graphics_ = h;
    useProgram(p.program);
    gl.glBindVertexArray(p.vao);
    // GL skips depth writes while the depth test is off; Vulkan does not.
    if (d.depthTest || d.depthWrite) {
        gl.glEnable(GL_DEPTH_TEST);
        gl.glDepthFunc(d.depthTest ? compareFunc(d.depthCompare) : GL_ALWAYS);
    } else {
        gl.glDisable(GL_DEPTH_TEST);
    }
    gl.glDepthMask(d.depthWrite ? GL_TRUE : GL_FALSE);
    // Like depth, GL writes the stencil only while its test is on, as Vulkan does.
    if (d.stencil.enabled) {
        gl.glEnable(GL_STENCIL_TEST);
        gl.glStencilFunc(compareFunc(d.stencil.compare), GLint(d.stencil.reference), d.stencil.readMask);
        gl.glStencilOp(GL_KEEP, GL_KEEP, d.stencil.pass == StencilOp::Replace ? GL_REPLACE : GL_KEEP);
        gl.glStencilMask(d.stencil.writeMask);
    } else {
        gl.glDisable(GL_STENCIL_TEST);
        gl.glStencilMask(0);
    }
    if (d.cull == CullMode::None) {
        gl.glDisable(GL_CULL_FACE);
    } else {
        gl.glEnable(GL_CULL_FACE);
        gl.glCullFace(d.cull == CullMode::Front ? GL_FRONT : GL_BACK);
    }
    // Both APIs put NDC y = -1 at row 0, but Vulkan's winding formula has the opposite sign to
    // GL's (its framebuffer y points down): the same triangle is CCW on one and CW on the other.
    gl.glFrontFace(d.frontFace == FrontFace::CounterClockwise ? GL_CW : GL_CCW);
    if (d.depthBiasConstant != 0.0f || d.depthBiasSlope != 0.0f) {
        gl.glEnable(GL_POLYGON_OFFSET_FILL);
        gl.glPolygonOffset(d.depthBiasSlope, d.depthBiasConstant);
    } else {
        gl.glDisable(GL_POLYGON_OFFSET_FILL);
    }
    for (uint32_t i = 0; i < RenderPassDesc::kMaxColorTargets; ++i) {
        const BlendState* b = nullptr;
        if (i < d.colorFormats.size() && !d.blend.empty())
            b = d.blend.size() == 1 ? &d.blend[0] : &d.blend[i];
        if (b && b->enabled) {
            gl.glEnablei(GL_BLEND, i);
            gl.glBlendFuncSeparatei(i, blendFactor(b->srcColor), blendFactor(b->dstColor),
                                    blendFactor(b->srcAlpha), blendFactor(b->dstAlpha));
            gl.glBlendEquationSeparatei(i, blendOp(b->colorOp), blendOp(b->alphaOp));
        } else {
            gl.glDisablei(GL_BLEND, i);
        }
    }
}

void GlCommandList::bindPipeline(ComputePipelineHandle h) {
    requireFrame("bindPipeline");
    useProgram(device_.computePipelines.get(h).program);
    compute_ = h;
}

void GlCommandList::bindVertexBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset) {
    requireFrame("bindVertexBuffer");
    const GlBuffer& b = device_.buffers.get(buffer);
    if (!(b.desc.usage & kBufferVertex)) throw Error("buffer '" + b.desc.debugName + "' lacks kBufferVertex");
    if (slot >= kMaxVertexBuffers)
        throw Error("bindVertexBuffer: slot " + std::to_string(slot) +
                    " >= " + std::to_string(kMaxVertexBuffers));
    vertexBuffers_[slot] = {b.id, offset};
}

void GlCommandList::bindIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset) {
    requireFrame("bindIndexBuffer");
    const GlBuffer& b = device_.buffers.get(buffer);
    if (!(b.desc.usage & kBufferIndex)) throw Error("buffer '" + b.desc.debugName + "' lacks kBufferIndex");
    indexBuffer_ = b.id;
    indexType_ = type;
    indexOffset_ = offset;
}

void GlCommandList::bindBuffer(GLenum target, uint32_t binding, BufferHandle buffer, uint64_t offset,
                               uint64_t size) {
    const bool storage = target == GL_SHADER_STORAGE_BUFFER;
    checkBinding(binding, storage ? "bindStorageBuffer" : "bindUniformBuffer");
    const GlBuffer& b = device_.buffers.get(buffer);
    if (!(b.desc.usage & (storage ? kBufferStorage : kBufferUniform)))
        throw Error("buffer '" + b.desc.debugName +
                    (storage ? "' lacks kBufferStorage" : "' lacks kBufferUniform"));
    if (offset >= b.desc.size) throw Error("buffer '" + b.desc.debugName + "': binding offset past its end");
    if (size == kWholeSize) size = b.desc.size - offset;
    if (size > b.desc.size - offset)
        throw Error("buffer '" + b.desc.debugName + "': bound range exceeds its size");
    device_.gl().glBindBufferRange(target, binding, b.id, GLintptr(offset), GLsizeiptr(size));
    bound_[binding] = GlHazards::bufferKey(b.id);
}

void GlCommandList::bindUniformBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size) {
    bindBuffer(GL_UNIFORM_BUFFER, binding, buffer, offset, size);
}

void GlCommandList::bindStorageBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size) {
    bindBuffer(GL_SHADER_STORAGE_BUFFER, binding, buffer, offset, size);
}

void GlCommandList::bindTexture(uint32_t binding, TextureHandle texture, SamplerHandle sampler) {
    checkBinding(binding, "bindTexture");
    const GlTexture& t = device_.textures.get(texture);
    const GlSampler& s = device_.samplers.get(sampler);
    if (!(t.desc.usage & kTextureSampled))
        throw Error("texture '" + t.desc.debugName + "' lacks kTextureSampled");
    // Integer formats have no filtering; a linear sampler would make the texture incomplete.
    if (isIntegerFormat(t.desc.format) &&
        (s.desc.minFilter == Filter::Linear || s.desc.magFilter == Filter::Linear ||
         (s.desc.mipFilter == Filter::Linear && t.desc.mipLevels > 1)))
        throw Error("texture '" + t.desc.debugName + "' (" + std::string(formatName(t.desc.format)) +
                    ") cannot be sampled with a linear filter");
    const Functions& gl = device_.gl();
    gl.glBindTextureUnit(binding, t.id);
    gl.glBindSampler(binding, s.id);
    bound_[binding] = GlHazards::textureKey(t.id);
}

void GlCommandList::bindStorageImage(uint32_t binding, TextureHandle texture, uint32_t mipLevel) {
    checkBinding(binding, "bindStorageImage");
    validateStorageImageBinding(binding, device_.caps(), "bindStorageImage");
    const GlTexture& t = device_.textures.get(texture);
    if (!(t.desc.usage & kTextureStorage))
        throw Error("texture '" + t.desc.debugName + "' lacks kTextureStorage");
    if (mipLevel >= t.desc.mipLevels)
        throw Error("texture '" + t.desc.debugName + "' has no mip " + std::to_string(mipLevel));
    // Layered: a 3D or array image is bound whole, as a Vulkan storage image view of it is.
    const GLboolean layered = t.desc.kind == TextureKind::Tex2D ? GL_FALSE : GL_TRUE;
    device_.gl().glBindImageTexture(binding, t.id, GLint(mipLevel), layered, 0, GL_READ_WRITE,
                                    glFormat(t.desc.format).internal);
    bound_[binding] = GlHazards::textureKey(t.id);
}

void GlCommandList::pushUniforms(uint32_t binding, const void* data, uint32_t size) {
    checkBinding(binding, "pushUniforms");
    if (!data || size == 0) throw Error("pushUniforms: no data");
    const uint64_t offset = device_.uniformRing().push(data, size);
    device_.gl().glBindBufferRange(GL_UNIFORM_BUFFER, binding, device_.uniformRing().buffer(),
                                   GLintptr(offset), GLsizeiptr(size));
    bound_[binding] = 0; // written by the host, before the frame's commands run: no hazard
}

GlGraphicsPipeline& GlCommandList::prepareDraw(const char* what, bool indexed) {
    requirePass(true, what);
    if (!graphics_) throw Error(std::string(what) + " without a graphics pipeline");
    GlGraphicsPipeline& p = device_.graphicsPipelines.get(graphics_);
    GLbitfield bits = shaderHazards(p.bindings);
    for (size_t i = 0; i < p.desc.vertexBuffers.size(); ++i)
        bits |= hazards_.beforeRead(GlHazards::bufferKey(vertexBuffers_[i].buffer),
                                    GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
    if (indexed)
        bits |= hazards_.beforeRead(GlHazards::bufferKey(indexBuffer_), GL_ELEMENT_ARRAY_BARRIER_BIT);
    barrier(bits);
    useProgram(p.program);
    const Functions& gl = device_.gl();
    const auto& layouts = p.desc.vertexBuffers;
    for (size_t i = 0; i < layouts.size(); ++i)
        gl.glVertexArrayVertexBuffer(p.vao, GLuint(i), vertexBuffers_[i].buffer,
                                     GLintptr(vertexBuffers_[i].offset), GLsizei(layouts[i].stride));
    return p;
}

void GlCommandList::draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                         uint32_t firstInstance) {
    const GlGraphicsPipeline& p = prepareDraw("draw", false);
    const Functions& gl = device_.gl();
    if (p.baseInstanceLocation >= 0) gl.glUniform1i(p.baseInstanceLocation, GLint(firstInstance));
    gl.glDrawArraysInstancedBaseInstance(primitiveMode(p.desc.topology), GLint(firstVertex),
                                         GLsizei(vertexCount), GLsizei(instanceCount), firstInstance);
    ++counts_.draws;
    countStage(counts_.barriers);
    noteShaderAccesses(p.bindings);
}

void GlCommandList::drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex,
                                int32_t vertexOffset, uint32_t firstInstance) {
    if (!indexBuffer_) throw Error("drawIndexed without an index buffer");
    const GlGraphicsPipeline& p = prepareDraw("drawIndexed", true);
    const Functions& gl = device_.gl();
    gl.glVertexArrayElementBuffer(p.vao, indexBuffer_);
    if (p.baseInstanceLocation >= 0) gl.glUniform1i(p.baseInstanceLocation, GLint(firstInstance));
    const bool u16 = indexType_ == IndexType::Uint16;
    const uint64_t byteOffset = indexOffset_ + uint64_t(firstIndex) * (u16 ? 2 : 4);
    gl.glDrawElementsInstancedBaseVertexBaseInstance(primitiveMode(p.desc.topology), GLsizei(indexCount),
                                                     u16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                                                     reinterpret_cast<const void*>(uintptr_t(byteOffset)),
                                                     GLsizei(instanceCount), vertexOffset, firstInstance);
    ++counts_.drawsIndexed;
    countStage(counts_.barriers);
    noteShaderAccesses(p.bindings);
}

void GlCommandList::drawIndexedIndirect(BufferHandle commands, uint64_t offset, uint32_t drawCount) {
    if (!device_.caps().multiDrawIndirect) throw Error("drawIndexedIndirect: no Caps::multiDrawIndirect");
    if (!indexBuffer_) throw Error("drawIndexedIndirect without an index buffer");
    if (indexOffset_ != 0) throw Error("drawIndexedIndirect: the index buffer is bound at an offset");
    const GlBuffer& b = device_.buffers.get(commands);
    if (!(b.desc.usage & kBufferIndirect) || b.desc.access != MemoryAccess::HostWrite)
        throw Error("drawIndexedIndirect: buffer '" + b.desc.debugName +
                    "' is not a HostWrite kBufferIndirect one");
    const GlGraphicsPipeline& p = prepareDraw("drawIndexedIndirect", true);
    // SPIRV-Cross's stand-in for the base instance is one uniform a call: a multi-draw's later
    // draws would read the first one's records.
    if (p.baseInstanceLocation >= 0)
        throw Error("drawIndexedIndirect: pipeline '" + p.desc.debugName +
                    "' reads gl_InstanceIndex, which GL gives a multi-draw's draws wrong");
    const Functions& gl = device_.gl();
    gl.glVertexArrayElementBuffer(p.vao, indexBuffer_);
    gl.glBindBuffer(GL_DRAW_INDIRECT_BUFFER, b.id);
    gl.glMultiDrawElementsIndirect(primitiveMode(p.desc.topology),
                                   indexType_ == IndexType::Uint16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
                                   reinterpret_cast<const void*>(uintptr_t(offset)), GLsizei(drawCount),
                                   GLsizei(sizeof(DrawIndexedIndirectCommand)));
    gl.glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    ++counts_.drawsIndexed;
    countStage(counts_.barriers);
    noteShaderAccesses(p.bindings);
}

void GlCommandList::dispatch(uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) {
    requirePass(false, "dispatch");
    if (!compute_) throw Error("dispatch without a compute pipeline");
    const GlComputePipeline& p = device_.computePipelines.get(compute_);
    barrier(shaderHazards(p.bindings));
    useProgram(p.program);
    device_.gl().glDispatchCompute(groupsX, groupsY, groupsZ);
    ++counts_.dispatches;
    countStage(counts_.barriers);
    // Its stores become visible to the later commands that touch them, at their barrier.
    noteShaderAccesses(p.bindings);
    conservativeBarrier();
}

void GlCommandList::clearTexture(TextureHandle texture, const std::array<float, 4>& value) {
    requirePass(false, "clearTexture");
    const GlTexture& t = device_.textures.get(texture);
    barrier(hazards_.beforeCommandWrite(GlHazards::textureKey(t.id), GL_TEXTURE_UPDATE_BARRIER_BIT));
    const Functions& gl = device_.gl();
    for (uint32_t mip = 0; mip < t.desc.mipLevels; ++mip) {
        if (isIntegerFormat(t.desc.format)) {
            const GLuint v[4] = {clearUint(value[0]), clearUint(value[1]), clearUint(value[2]),
                                 clearUint(value[3])};
            gl.glClearTexImage(t.id, GLint(mip), GL_RGBA_INTEGER, GL_UNSIGNED_INT, v);
        } else if (isDepthFormat(t.desc.format)) {
            gl.glClearTexImage(t.id, GLint(mip), GL_DEPTH_COMPONENT, GL_FLOAT, &value[0]);
        } else if (t.desc.format == Format::RGBA8Srgb) {
            const float encoded[4] = {linearToSrgb(value[0]), linearToSrgb(value[1]), linearToSrgb(value[2]),
                                      value[3]};
            gl.glClearTexImage(t.id, GLint(mip), GL_RGBA, GL_FLOAT, encoded);
        } else {
            gl.glClearTexImage(t.id, GLint(mip), GL_RGBA, GL_FLOAT, value.data());
        }
    }
    conservativeBarrier();
}

void GlCommandList::updateBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint32_t size) {
    requirePass(false, "updateBuffer");
    const GlBuffer& b = device_.buffers.get(buffer);
    if (!data || size == 0 || size > 65536 || size % 4 != 0 || offset % 4 != 0)
        throw Error("updateBuffer '" + b.desc.debugName +
                    "': size must be 4..65536 and offset and size multiples of 4");
    if (offset > b.desc.size || size > b.desc.size - offset)
        throw Error("updateBuffer '" + b.desc.debugName + "': range exceeds its size");
    // In stream: GL orders the update after the draws and dispatches issued before it, once
    // their stores to the buffer are complete.
    barrier(hazards_.beforeCommandWrite(GlHazards::bufferKey(b.id), GL_BUFFER_UPDATE_BARRIER_BIT));
    device_.gl().glNamedBufferSubData(b.id, GLintptr(offset), GLsizeiptr(size), data);
    conservativeBarrier();
}

void GlCommandList::copyTextures(std::span<const TextureCopy> copies) {
    requirePass(false, "copyTextures");
    validateTextureCopies(
        copies, [&](TextureHandle t) -> const TextureDesc& { return device_.textures.get(t).desc; });
    // No barrier bit names glCopyImageSubData: after shader stores to any of the textures, every
    // bit, once for all the copies.
    bool hazard = false;
    for (const TextureCopy& c : copies) {
        hazard |=
            hazards_.beforeRead(GlHazards::textureKey(device_.textures.get(c.src).id), GL_ALL_BARRIER_BITS);
        hazard |= hazards_.beforeCommandWrite(GlHazards::textureKey(device_.textures.get(c.dst).id),
                                              GL_ALL_BARRIER_BITS);
    }
    if (hazard) barrier(GL_ALL_BARRIER_BITS);
    const Functions& gl = device_.gl();
    for (const TextureCopy& c : copies) {
        const GlTexture& s = device_.textures.get(c.src);
        const GlTexture& d = device_.textures.get(c.dst);
        gl.glCopyImageSubData(s.id, s.target, 0, 0, 0, 0, d.id, d.target, 0, 0, 0, 0, GLsizei(s.desc.width),
                              GLsizei(s.desc.height), GLsizei(s.desc.depthOrLayers));
    }
    conservativeBarrier();
}

void GlCommandList::writeTimestamp(uint32_t slot) {
    requireFrame("writeTimestamp");
    device_.timestamps().write(device_.frameIndex(), slot);
}

void GlCommandList::beginMarker(const char* name) {
    requireFrame("beginMarker");
    device_.gl().glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name ? name : "");
    ++markerDepth_;
}

void GlCommandList::endMarker() {
    requireFrame("endMarker");
    if (markerDepth_ == 0) throw Error("endMarker without beginMarker");
    device_.gl().glPopDebugGroup();
    --markerDepth_;
}

} // namespace lpv::rhi::gl
