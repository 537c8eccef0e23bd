// OpenGL command recording: each call runs on the context in recording order.
#include "GlDevice.h"

#include "GlFormats.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::gl {

void GlCommandList::reset() {
    inPass_ = false;
    graphics_ = nullptr;
    graphicsHandle_ = {};
    vertexBuffers_ = {};
    indexBuffer_ = 0;
}

void GlCommandList::requireOutsidePass(const char* what) const {
    if (inPass_) throw Error(std::string(what) + " inside a render pass");
}

void GlCommandList::beginRenderPass(const RenderPassDesc& desc) {
    requireOutsidePass("beginRenderPass");
    const Functions& gl = device_.gl();
    const GLuint fbo = device_.framebufferFor(desc);
    gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    // Clears obey the write masks and the scissor: open them first.
    gl.glDisable(GL_SCISSOR_TEST);
    for (uint32_t i = 0; i < desc.colorCount; ++i) {
        const ColorAttachment& c = desc.colors[i];
        if (c.load != LoadOp::Clear) continue;
        gl.glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        if (device_.textures.get(c.texture).desc.format == Format::R32UI) {
            const GLuint v[4] = {GLuint(c.clearColor[0]), GLuint(c.clearColor[1]), GLuint(c.clearColor[2]),
                                 GLuint(c.clearColor[3])};
            gl.glClearNamedFramebufferuiv(fbo, GL_COLOR, GLint(i), v);
        } else {
            gl.glClearNamedFramebufferfv(fbo, GL_COLOR, GLint(i), c.clearColor.data());
        }
    }
    if (desc.depth.texture && desc.depth.load == LoadOp::Clear) {
        gl.glDepthMask(GL_TRUE);
        gl.glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &desc.depth.clearDepth);
    }
    const TextureHandle first = desc.colorCount ? desc.colors[0].texture : desc.depth.texture;
    const TextureDesc& d = device_.textures.get(first).desc;
    const uint32_t mip = desc.colorCount ? desc.colors[0].mipLevel : 0;
    passWidth_ = std::max(1u, d.width >> mip);
    passHeight_ = std::max(1u, d.height >> mip);
    gl.glViewportIndexedf(0, 0, 0, float(passWidth_), float(passHeight_));
    gl.glDepthRangef(0.0f, 1.0f);
    gl.glEnable(GL_SCISSOR_TEST);
    gl.glScissor(0, 0, GLsizei(passWidth_), GLsizei(passHeight_));
    gl.glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, desc.debugName);
    inPass_ = true;
}

void GlCommandList::endRenderPass() {
    if (!inPass_) throw Error("endRenderPass without beginRenderPass");
    const Functions& gl = device_.gl();
    gl.glPopDebugGroup();
    gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl.glMemoryBarrier(GL_ALL_BARRIER_BITS);
    inPass_ = false;
}

void GlCommandList::setViewport(const Viewport& vp) {
    device_.gl().glViewportIndexedf(0, vp.x, vp.y, vp.width, vp.height);
    device_.gl().glDepthRangef(vp.minDepth, vp.maxDepth);
}

void GlCommandList::setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) {
    device_.gl().glScissor(x, y, GLsizei(width), GLsizei(height));
}

void GlCommandList::bindPipeline(GraphicsPipelineHandle h) {
    GlGraphicsPipeline& p = device_.graphicsPipelines.get(h);
    const Functions& gl = device_.gl();
    const GraphicsPipelineDesc& d = p.desc;
    graphics_ = &p;
    graphicsHandle_ = h;
    gl.glUseProgram(p.program);
    gl.glBindVertexArray(p.vao);
    if (d.depthTest || d.depthWrite) {
        gl.glEnable(GL_DEPTH_TEST);
        gl.glDepthFunc(d.depthTest ? compareFunc(d.depthCompare) : GL_ALWAYS);
    } else {
        gl.glDisable(GL_DEPTH_TEST);
    }
    gl.glDepthMask(d.depthWrite ? GL_TRUE : GL_FALSE);
    if (d.cull == CullMode::None) {
        gl.glDisable(GL_CULL_FACE);
    } else {
        gl.glEnable(GL_CULL_FACE);
        gl.glCullFace(d.cull == CullMode::Front ? GL_FRONT : GL_BACK);
    }
    // Vulkan judges winding with y pointing down the framebuffer and GL with y up, while both put
    // NDC y = -1 at row 0: the same triangle is counter-clockwise on one and clockwise on the other.
    gl.glFrontFace(d.frontFace == FrontFace::CounterClockwise ? GL_CW : GL_CCW);
    if (d.depthBiasConstant != 0.0f || d.depthBiasSlope != 0.0f) {
        gl.glEnable(GL_POLYGON_OFFSET_FILL);
        gl.glPolygonOffset(d.depthBiasSlope, d.depthBiasConstant);
    } else {
        gl.glDisable(GL_POLYGON_OFFSET_FILL);
    }
    for (uint32_t i = 0; i < RenderPassDesc::kMaxColorTargets; ++i) {
        gl.glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        const BlendState* b =
            d.blend.empty()
                ? nullptr
                : (d.blend.size() == 1 ? &d.blend[0] : (i < d.blend.size() ? &d.blend[i] : nullptr));
        if (b && b->enabled && i < d.colorFormats.size()) {
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
    const GlComputePipeline& p = device_.computePipelines.get(h);
    device_.gl().glUseProgram(p.program);
    graphics_ = nullptr;
}

void GlCommandList::bindVertexBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset) {
    if (slot >= vertexBuffers_.size())
        throw Error("vertex buffer slot " + std::to_string(slot) + " out of range");
    vertexBuffers_[slot] = {device_.buffers.get(buffer).id, offset};
}

void GlCommandList::bindIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset) {
    indexBuffer_ = device_.buffers.get(buffer).id;
    indexType_ = type;
    indexOffset_ = offset;
}

void GlCommandList::bindUniformBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size) {
    const GlBuffer& b = device_.buffers.get(buffer);
    device_.gl().glBindBufferRange(GL_UNIFORM_BUFFER, binding, b.id, GLintptr(offset),
                                   GLsizeiptr(size == kWholeSize ? b.desc.size - offset : size));
}

void GlCommandList::bindStorageBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size) {
    const GlBuffer& b = device_.buffers.get(buffer);
    device_.gl().glBindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, b.id, GLintptr(offset),
                                   GLsizeiptr(size == kWholeSize ? b.desc.size - offset : size));
}

void GlCommandList::bindTexture(uint32_t binding, TextureHandle texture, SamplerHandle sampler) {
    const Functions& gl = device_.gl();
    gl.glBindTextureUnit(binding, device_.textures.get(texture).id);
    gl.glBindSampler(binding, device_.samplers.get(sampler).id);
}

void GlCommandList::bindStorageImage(uint32_t binding, TextureHandle texture, uint32_t mipLevel) {
    const GlTexture& t = device_.textures.get(texture);
    const GLboolean layered = t.desc.kind == TextureKind::Tex2D ? GL_FALSE : GL_TRUE;
    device_.gl().glBindImageTexture(binding, t.id, GLint(mipLevel), layered, 0, GL_READ_WRITE,
                                    glFormat(t.desc.format).internal);
}

void GlCommandList::pushUniforms(uint32_t binding, const void* data, uint32_t size) {
    const uint64_t offset = device_.allocateUniforms(data, size);
    device_.gl().glBindBufferRange(GL_UNIFORM_BUFFER, binding, device_.uniformRing(), GLintptr(offset), size);
}

void GlCommandList::prepareDraw() {
    if (!inPass_) throw Error("draw outside a render pass");
    if (!graphics_) throw Error("draw without a graphics pipeline");
    const Functions& gl = device_.gl();
    const auto& layouts = graphics_->desc.vertexBuffers;
    for (size_t i = 0; i < layouts.size(); ++i)
        gl.glVertexArrayVertexBuffer(graphics_->vao, GLuint(i), vertexBuffers_[i].buffer,
                                     GLintptr(vertexBuffers_[i].offset), GLsizei(layouts[i].stride));
}

void GlCommandList::draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                         uint32_t firstInstance) {
    prepareDraw();
    const Functions& gl = device_.gl();
    if (graphics_->baseInstanceLocation >= 0)
        gl.glUniform1i(graphics_->baseInstanceLocation, GLint(firstInstance));
    gl.glDrawArraysInstancedBaseInstance(primitiveMode(graphics_->desc.topology), GLint(firstVertex),
                                         GLsizei(vertexCount), GLsizei(instanceCount), firstInstance);
}

void GlCommandList::drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex,
                                int32_t vertexOffset, uint32_t firstInstance) {
    prepareDraw();
    if (!indexBuffer_) throw Error("drawIndexed without an index buffer");
    const Functions& gl = device_.gl();
    gl.glVertexArrayElementBuffer(graphics_->vao, indexBuffer_);
    if (graphics_->baseInstanceLocation >= 0)
        gl.glUniform1i(graphics_->baseInstanceLocation, GLint(firstInstance));
    const uint64_t indexSize = indexType_ == IndexType::Uint16 ? 2 : 4;
    gl.glDrawElementsInstancedBaseVertexBaseInstance(
        primitiveMode(graphics_->desc.topology), GLsizei(indexCount),
        indexType_ == IndexType::Uint16 ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(uintptr_t(indexOffset_ + uint64_t(firstIndex) * indexSize)),
        GLsizei(instanceCount), vertexOffset, firstInstance);
}

void GlCommandList::dispatch(uint32_t x, uint32_t y, uint32_t z) {
    requireOutsidePass("dispatch");
    const Functions& gl = device_.gl();
    gl.glDispatchCompute(x, y, z);
    gl.glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void GlCommandList::clearTexture(TextureHandle texture, const std::array<float, 4>& value) {
    requireOutsidePass("clearTexture");
    const GlTexture& t = device_.textures.get(texture);
    const GlFormat f = glFormat(t.desc.format);
    const Functions& gl = device_.gl();
    for (uint32_t mip = 0; mip < t.desc.mipLevels; ++mip) {
        if (t.desc.format == Format::R32UI) {
            const GLuint v = GLuint(value[0]);
            gl.glClearTexImage(t.id, GLint(mip), GL_RED_INTEGER, GL_UNSIGNED_INT, &v);
        } else if (t.desc.format == Format::D32F) {
            gl.glClearTexImage(t.id, GLint(mip), GL_DEPTH_COMPONENT, GL_FLOAT, &value[0]);
        } else {
            gl.glClearTexImage(t.id, GLint(mip), GL_RGBA, GL_FLOAT, value.data());
        }
    }
    (void)f;
    gl.glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void GlCommandList::updateBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint32_t size) {
    requireOutsidePass("updateBuffer");
    const GlBuffer& b = device_.buffers.get(buffer);
    if (offset + size > b.desc.size)
        throw Error("updateBuffer: range exceeds buffer '" + b.desc.debugName + "'");
    device_.gl().glNamedBufferSubData(b.id, GLintptr(offset), size, data);
}

void GlCommandList::copyTexture(TextureHandle src, TextureHandle dst) {
    requireOutsidePass("copyTexture");
    const GlTexture& s = device_.textures.get(src);
    const GlTexture& d = device_.textures.get(dst);
    if (s.desc.width != d.desc.width || s.desc.height != d.desc.height ||
        s.desc.depthOrLayers != d.desc.depthOrLayers)
        throw Error("copyTexture: '" + s.desc.debugName + "' and '" + d.desc.debugName + "' differ in size");
    device_.gl().glCopyImageSubData(s.id, s.target, 0, 0, 0, 0, d.id, d.target, 0, 0, 0, 0,
                                    GLsizei(s.desc.width), GLsizei(s.desc.height),
                                    GLsizei(s.desc.depthOrLayers));
    device_.gl().glMemoryBarrier(GL_ALL_BARRIER_BITS);
}

void GlCommandList::writeTimestamp(uint32_t slot) {
    device_.recordTimestamp(slot);
}

void GlCommandList::beginMarker(const char* name) {
    device_.gl().glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name);
}

void GlCommandList::endMarker() {
    device_.gl().glPopDebugGroup();
}

} // namespace lpv::rhi::gl
