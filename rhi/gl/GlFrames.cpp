// Frames of the GL backend: the frames-in-flight fences, presentation to a window and timestamp
// readback. A fence per frame slot bounds how far the CPU runs ahead, exactly as the Vulkan
// backend's frame fences do, and guards that slot's region of the uniform ring.
#include "GlDevice.h"

#include "platforms/Window.h"
#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::gl {

CommandList& GlDevice::beginFrame() {
    if (inFrame_) throw Error("beginFrame() called twice without endFrame()");
    const uint32_t slot = uint32_t((frame_ + 1) % fences_.size());
    // Wait for the frame that last used this slot (framesInFlight frames ago).
    if (GLsync& fence = fences_[slot]) {
        while (gl_.glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000ull) == GL_TIMEOUT_EXPIRED) {
        }
        gl_.glDeleteSync(fence);
        fence = nullptr;
    }
    ++frame_;
    timestamps_.beginFrame(frame_);
    uniformRing_.beginFrame(slot);
    inFrame_ = true;
    list_.begin();
    return list_;
}

void GlDevice::endFrame(TextureHandle presentTexture) {
    if (!inFrame_) throw Error("endFrame() without beginFrame()");
    const bool paid = list_.finish();
    if (presentTexture) {
        const GlTexture& source = textures.get(presentTexture);
        if (isIntegerFormat(source.desc.format) || isDepthFormat(source.desc.format))
            throw Error("endFrame: texture '" + source.desc.debugName + "' (" +
                        std::string(formatName(source.desc.format)) + ") cannot be presented");
        if (context_->hasDefaultFramebuffer()) present(source);
    }
    timestamps_.endFrame(frame_);
    // Shader writes to MemoryAccess::HostRead buffers reach their persistent mappings by the time
    // the fence below signals, for beginFrame()'s wait to make them readable (finish()'s barrier,
    // when it paid one, had every bit).
    if (!paid) {
        gl_.glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
        list_.countBarrier();
    }
    lastFrame_ = list_.counts();
    fences_[frame_ % fences_.size()] = gl_.glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl_.glFlush(); // "submit": the driver starts on the frame now
    inFrame_ = false;
}

void GlDevice::present(const GlTexture& source) {
    uint32_t width = source.desc.width, height = source.desc.height;
    if (config_.window) config_.window->framebufferSize(width, height); // follows resizes
    if (width == 0 || height == 0) return;                              // minimized: nothing to show
    if (!presentFramebuffer_) {
        gl_.glCreateFramebuffers(1, &presentFramebuffer_);
        label_(GL_FRAMEBUFFER, presentFramebuffer_, "present source");
    }
    if (source.desc.kind == TextureKind::Tex2D)
        gl_.glNamedFramebufferTexture(presentFramebuffer_, GL_COLOR_ATTACHMENT0, source.id, 0);
    else
        gl_.glNamedFramebufferTextureLayer(presentFramebuffer_, GL_COLOR_ATTACHMENT0, source.id, 0, 0);
    gl_.glNamedFramebufferReadBuffer(presentFramebuffer_, GL_COLOR_ATTACHMENT0);
    // A plain copy of the stored values, scaled with linear filtering and flipped (destination
    // y0 = height, y1 = 0) so memory row 0 shows at the top of the window, as on Vulkan.
    gl_.glDisable(GL_FRAMEBUFFER_SRGB);
    gl_.glDisable(GL_SCISSOR_TEST);
    gl_.glBlitNamedFramebuffer(presentFramebuffer_, 0, 0, 0, GLint(source.desc.width),
                               GLint(source.desc.height), 0, GLint(height), GLint(width), 0,
                               GL_COLOR_BUFFER_BIT, GL_LINEAR);
    gl_.glEnable(GL_FRAMEBUFFER_SRGB);
    // Detach so a later destroy() of the texture leaves no dangling attachment behind.
    gl_.glNamedFramebufferTexture(presentFramebuffer_, GL_COLOR_ATTACHMENT0, 0, 0);
    context_->swapBuffers();
}

bool GlDevice::readTimestamps(uint64_t frame, std::span<uint64_t> nanoseconds) {
    return timestamps_.read(frame, nanoseconds);
}

} // namespace lpv::rhi::gl
