// Immediate transfers of the GL backend: uploads and readbacks between frames. GL orders them
// after every command issued before, and readbacks return once the data is there, so no explicit
// waiting is needed.
#include "GlDevice.h"
#include "GlFormats.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::gl {
namespace {

void checkBufferRange(const GlBuffer& b, uint64_t offset, uint64_t size, const char* what) {
    if (offset > b.desc.size || size > b.desc.size - offset)
        throw Error(std::string(what) + " '" + b.desc.debugName + "': range [" + std::to_string(offset) +
                    ", " + std::to_string(offset + size) + ") exceeds its size " +
                    std::to_string(b.desc.size));
}

} // namespace

void GlDevice::requireOutsideFrame(const char* what) const {
    if (inFrame_)
        throw Error(std::string(what) + " inside a frame: immediate transfers wait for the GPU; call it "
                                        "before beginFrame() or after endFrame()");
}

const GlTexture& GlDevice::transferTexture(TextureHandle h, uint32_t mip, uint64_t size,
                                           const char* what) const {
    const GlTexture& t = textures.get(h);
    if (mip >= t.desc.mipLevels)
        throw Error(std::string(what) + " '" + t.desc.debugName + "': no mip " + std::to_string(mip));
    if (size != t.mipBytes(mip))
        throw Error(std::string(what) + " '" + t.desc.debugName + "' mip " + std::to_string(mip) + ": " +
                    std::to_string(size) + " bytes given, " + std::to_string(t.mipBytes(mip)) +
                    " expected (tightly packed, all layers)");
    return t;
}

void GlDevice::uploadBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) {
    requireOutsideFrame("uploadBuffer");
    const GlBuffer& b = buffers.get(h);
    checkBufferRange(b, offset, size, "uploadBuffer");
    if (size > 0) gl_.glNamedBufferSubData(b.id, GLintptr(offset), GLsizeiptr(size), data);
}

void GlDevice::uploadTexture(TextureHandle h, uint32_t mip, const void* data, uint64_t size) {
    requireOutsideFrame("uploadTexture");
    const GlTexture& t = transferTexture(h, mip, size, "uploadTexture");
    const GlFormat f = glFormat(t.desc.format);
    const GLsizei w = GLsizei(t.width(mip)), hgt = GLsizei(t.height(mip));
    if (t.desc.kind == TextureKind::Tex2D)
        gl_.glTextureSubImage2D(t.id, GLint(mip), 0, 0, w, hgt, f.format, f.type, data);
    else
        gl_.glTextureSubImage3D(t.id, GLint(mip), 0, 0, 0, w, hgt, GLsizei(t.depthOrLayers(mip)), f.format,
                                f.type, data);
}

void GlDevice::readBuffer(BufferHandle h, uint64_t offset, void* out, uint64_t size) {
    requireOutsideFrame("readBuffer");
    const GlBuffer& b = buffers.get(h);
    checkBufferRange(b, offset, size, "readBuffer");
    if (size == 0) return;
    if (b.mapped) {
        gl_.glGetNamedBufferSubData(b.id, GLintptr(offset), GLsizeiptr(size), out);
        return;
    }
    // Through a client-storage copy: reading a GPU-only buffer directly makes NVIDIA's driver move
    // it from video to host memory (and say so in a performance warning) after a few readbacks.
    // Readbacks happen between frames, so the copy is made and freed here.
    GLuint staging = 0;
    gl_.glCreateBuffers(1, &staging);
    gl_.glNamedBufferStorage(staging, GLsizeiptr(size), nullptr, GL_CLIENT_STORAGE_BIT | GL_MAP_READ_BIT);
    gl_.glCopyNamedBufferSubData(b.id, staging, GLintptr(offset), 0, GLsizeiptr(size));
    gl_.glGetNamedBufferSubData(staging, 0, GLsizeiptr(size), out);
    gl_.glDeleteBuffers(1, &staging);
}

void GlDevice::readTexture(TextureHandle h, uint32_t mip, void* out, uint64_t size) {
    requireOutsideFrame("readTexture");
    const GlTexture& t = transferTexture(h, mip, size, "readTexture");
    const GlFormat f = glFormat(t.desc.format);
    // Whole mip, every layer or slice in order, row 0 first: GL's image order is the RHI's.
    gl_.glGetTextureImage(t.id, GLint(mip), f.format, f.type, GLsizei(size), out);
}

void* GlDevice::mapped(BufferHandle h) {
    GlBuffer& b = buffers.get(h);
    if (!b.mapped)
        throw Error("buffer '" + b.desc.debugName + "' is not MemoryAccess::HostWrite or HostRead");
    return b.mapped;
}

} // namespace lpv::rhi::gl
