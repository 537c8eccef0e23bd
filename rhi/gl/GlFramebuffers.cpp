// Framebuffer cache of the GL backend (see GlFramebuffers.h). DSA calls only.
#include "GlFramebuffers.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::gl {

void GlFramebufferCache::init(const Functions& gl, const ObjectLabeler& label) {
    gl_ = &gl;
    label_ = &label;
    key_.reserve(1 + 2 * (RenderPassDesc::kMaxColorTargets + 1));
}

void GlFramebufferCache::destroy() {
    for (auto& [key, fbo] : framebuffers_)
        gl_->glDeleteFramebuffers(1, &fbo);
    framebuffers_.clear();
}

GLuint GlFramebufferCache::get(const GlAttachment* colors, uint32_t colorCount, const GlAttachment* depth,
                               const char* name) {
    key_.clear();
    key_.push_back(colorCount | (depth ? 0x100u : 0u));
    auto addKey = [&](const GlAttachment& a) {
        key_.push_back(a.texture);
        key_.push_back((uint64_t(a.oneLayer) << 63) | (uint64_t(a.mipLevel) << 32) | a.layer);
    };
    for (uint32_t i = 0; i < colorCount; ++i)
        addKey(colors[i]);
    if (depth) addKey(*depth);
    if (auto it = framebuffers_.find(key_); it != framebuffers_.end()) return it->second;

    GLuint fbo = 0;
    gl_->glCreateFramebuffers(1, &fbo);
    auto attach = [&](GLenum point, const GlAttachment& a) {
        if (a.oneLayer)
            gl_->glNamedFramebufferTextureLayer(fbo, point, a.texture, GLint(a.mipLevel), GLint(a.layer));
        else
            gl_->glNamedFramebufferTexture(fbo, point, a.texture, GLint(a.mipLevel));
    };
    GLenum drawBuffers[RenderPassDesc::kMaxColorTargets];
    for (uint32_t i = 0; i < colorCount; ++i) {
        attach(GL_COLOR_ATTACHMENT0 + i, colors[i]);
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    if (depth) attach(depth->stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, *depth);
    if (colorCount > 0)
        gl_->glNamedFramebufferDrawBuffers(fbo, GLsizei(colorCount), drawBuffers);
    else
        gl_->glNamedFramebufferDrawBuffer(fbo, GL_NONE); // depth-only pass (shadow maps, RSM depth)
    gl_->glNamedFramebufferReadBuffer(fbo, colorCount > 0 ? GL_COLOR_ATTACHMENT0 : GL_NONE);
    const GLenum status = gl_->glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        gl_->glDeleteFramebuffers(1, &fbo);
        throw Error(std::string("OpenGL: render pass '") + name + "': framebuffer incomplete (status " +
                    std::to_string(status) + ")");
    }
    (*label_)(GL_FRAMEBUFFER, fbo, name);
    framebuffers_.emplace(key_, fbo);
    return fbo;
}

void GlFramebufferCache::forgetTexture(GLuint texture) {
    for (auto it = framebuffers_.begin(); it != framebuffers_.end();) {
        bool uses = false;
        for (size_t i = 1; i < it->first.size(); i += 2)
            uses = uses || it->first[i] == texture;
        if (uses) {
            gl_->glDeleteFramebuffers(1, &it->second);
            it = framebuffers_.erase(it);
        } else {
            ++it;
        }
    }
}

} // namespace lpv::rhi::gl
