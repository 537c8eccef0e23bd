// Buffers, textures and samplers of the GL backend. Deleting a GL object that queued commands
// still use is safe: the driver keeps it alive until they finish, which is the deferral the RHI
// asks of destroy().
#include "../src/DescValidation.h"
#include "GlDevice.h"
#include "GlFormats.h"

#include "rhi/Error.h"

#include <algorithm>
#include <string>

namespace lpv::rhi::gl {

BufferHandle GlDevice::createBuffer(const BufferDesc& desc, const void* initialData) {
    if (desc.size == 0) throw Error("buffer '" + desc.debugName + "': size is 0");
    GlBuffer b;
    b.desc = desc;
    gl_.glCreateBuffers(1, &b.id);
    const bool host = desc.access != MemoryAccess::GpuOnly;
    const GLbitfield mapFlags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT |
                                (desc.access == MemoryAccess::HostRead ? GL_MAP_READ_BIT : 0);
    // Dynamic storage: updateBuffer and uploadBuffer write through glNamedBufferSubData.
    gl_.glNamedBufferStorage(b.id, GLsizeiptr(desc.size), initialData,
                             GL_DYNAMIC_STORAGE_BIT | (host ? mapFlags : 0));
    if (host) b.mapped = gl_.glMapNamedBufferRange(b.id, 0, GLsizeiptr(desc.size), mapFlags);
    label_(GL_BUFFER, b.id, desc.debugName);
    const BufferHandle h = buffers.insert(std::move(b));
    allocations_.add(ResourceType::Buffer, h.bits,
                     {ResourceType::Buffer, desc.debugName, desc.category, desc.size});
    return h;
}

TextureHandle GlDevice::createTexture(const TextureDesc& desc) {
    validateTextureDesc(desc, caps_);

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
    label_(GL_TEXTURE, t.id, desc.debugName);
    const TextureHandle h = textures.insert(std::move(t));
    allocations_.add(ResourceType::Texture, h.bits,
                     {ResourceType::Texture, desc.debugName, desc.category, textureBytes(desc)});
    return h;
}

SamplerHandle GlDevice::createSampler(const SamplerDesc& d) {
    GlSampler s;
    s.desc = d;
    gl_.glCreateSamplers(1, &s.id);
    // Vulkan samplers always have a mip mode; with a single-mip texture both choices read mip 0.
    const bool linearMin = d.minFilter == Filter::Linear, linearMip = d.mipFilter == Filter::Linear;
    const GLenum minFilter = linearMin ? (linearMip ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST)
                                       : (linearMip ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST);
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_MIN_FILTER, GLint(minFilter));
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_MAG_FILTER,
                            d.magFilter == Filter::Linear ? GL_LINEAR : GL_NEAREST);
    const GLint wrap = GLint(addressMode(d.address));
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_WRAP_S, wrap);
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_WRAP_T, wrap);
    gl_.glSamplerParameteri(s.id, GL_TEXTURE_WRAP_R, wrap);
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f}; // VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE
    gl_.glSamplerParameterfv(s.id, GL_TEXTURE_BORDER_COLOR, white);
    if (d.maxAnisotropy > 1.0f) gl_.glSamplerParameterf(s.id, GL_TEXTURE_MAX_ANISOTROPY, d.maxAnisotropy);
    if (d.compareEnable) {
        gl_.glSamplerParameteri(s.id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        gl_.glSamplerParameteri(s.id, GL_TEXTURE_COMPARE_FUNC, GLint(compareFunc(d.compareOp)));
    }
    label_(GL_SAMPLER, s.id, d.debugName);
    return samplers.insert(std::move(s));
}

void GlDevice::destroy(BufferHandle h) {
    GlBuffer b = buffers.remove(h);
    gl_.glDeleteBuffers(1, &b.id);
    allocations_.remove(ResourceType::Buffer, h.bits);
}

void GlDevice::destroy(TextureHandle h) {
    GlTexture t = textures.remove(h);
    // GL reuses texture names: a cached framebuffer must not outlive its textures.
    framebuffers_.forgetTexture(t.id);
    gl_.glDeleteTextures(1, &t.id);
    allocations_.remove(ResourceType::Texture, h.bits);
}

void GlDevice::destroy(SamplerHandle h) {
    GlSampler s = samplers.remove(h);
    gl_.glDeleteSamplers(1, &s.id);
}

} // namespace lpv::rhi::gl
