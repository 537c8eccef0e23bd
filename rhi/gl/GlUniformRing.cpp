// Uniform ring of the GL backend (see GlUniformRing.h).
#include "GlUniformRing.h"

#include "rhi/Error.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace lpv::rhi::gl {

void GlUniformRing::create(const Functions& gl, uint64_t regionBytes, uint32_t regions) {
    gl_ = &gl;
    regionBytes_ = regionBytes;
    regions_ = regions;
    GLint align = 0;
    gl.glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &align);
    alignment_ = uint64_t(std::max(align, 16));
    const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    gl.glCreateBuffers(1, &buffer_);
    gl.glNamedBufferStorage(buffer_, GLsizeiptr(totalBytes()), nullptr, flags);
    mapped_ = static_cast<std::byte*>(gl.glMapNamedBufferRange(buffer_, 0, GLsizeiptr(totalBytes()), flags));
    if (!mapped_) throw Error("OpenGL: the uniform ring cannot be mapped");
}

void GlUniformRing::destroy() {
    if (buffer_) gl_->glDeleteBuffers(1, &buffer_); // unmaps too
    buffer_ = 0;
    mapped_ = nullptr;
}

void GlUniformRing::beginFrame(uint32_t region) {
    base_ = regionBytes_ * region;
    cursor_ = 0;
}

uint64_t GlUniformRing::push(const void* data, uint32_t size) {
    const uint64_t offset = (cursor_ + alignment_ - 1) / alignment_ * alignment_;
    if (offset + size > regionBytes_)
        throw Error("pushUniforms: more than " + std::to_string(regionBytes_) +
                    " bytes in one frame (raise DeviceConfig::uniformRingBytes)");
    cursor_ = offset + size;
    // Coherent mapping: the write is visible to every GL command issued after this one.
    std::memcpy(mapped_ + base_ + offset, data, size);
    return base_ + offset;
}

} // namespace lpv::rhi::gl
