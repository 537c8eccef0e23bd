// Which glMemoryBarrier bits a GL command needs (the RHI rule of CommandList.h on GL): only shader
// stores (storage images and buffers) are incoherent with later commands, so the list keeps the
// resources shaders stored to since a barrier made them visible, per kind of later access (one
// barrier bit each), and those shaders read, which a later store must not overtake. A command then
// pays one glMemoryBarrier with the bits its own accesses need, or none. Fixed storage, no heap.
#pragma once

#include <GL/glcorearb.h>

#include <array>
#include <cstdint>

namespace lpv::rhi::gl {

class GlHazards {
public:
    // Texture and buffer names are separate namespaces in GL.
    static uint64_t textureKey(GLuint id) { return id ? (uint64_t(1) << 32) | id : 0; }
    static uint64_t bufferKey(GLuint id) { return id ? (uint64_t(2) << 32) | id : 0; }

    // Bits needed before a shader or a fixed-function stage reads `key` through `access` (the one
    // barrier bit that orders that kind of read, e.g. GL_TEXTURE_FETCH_BARRIER_BIT).
    GLbitfield beforeRead(uint64_t key, GLbitfield access) const;
    // Before a shader stores to `key` through `access` (GL_SHADER_IMAGE_ACCESS_BARRIER_BIT or
    // GL_SHADER_STORAGE_BARRIER_BIT): earlier stores and reads finish first.
    GLbitfield beforeShaderWrite(uint64_t key, GLbitfield access) const;
    // Before a GL command (a clear, copy, update or a render target) writes `key`; `access` is the
    // bit that orders it after shader stores. After incoherent shader reads: every bit (the
    // barrier bits do not name that case).
    GLbitfield beforeCommandWrite(uint64_t key, GLbitfield access) const;

    // A glMemoryBarrier(bits) was recorded.
    void paid(GLbitfield bits);
    // A command's shaders stored to / read `key`; `incoherent`: through an image load or a
    // storage buffer (a texture fetch or a uniform read is ordered with later GL commands).
    // Return false when the list is full: pay every bit, then note again.
    bool noteWrite(uint64_t key);
    bool noteRead(uint64_t key, bool incoherent);
    bool empty() const { return writeCount_ == 0 && readCount_ == 0; }

private:
    struct Write {
        uint64_t key;
        GLbitfield invisible; // the kinds of later access that still need a barrier
    };
    struct Read {
        uint64_t key;
        bool incoherent;
    };
    const Write* findWrite(uint64_t key) const;
    const Read* findRead(uint64_t key) const;

    static constexpr uint32_t kMaxTracked = 64;
    std::array<Write, kMaxTracked> writes_{};
    std::array<Read, kMaxTracked> reads_{};
    uint32_t writeCount_ = 0, readCount_ = 0;
};

} // namespace lpv::rhi::gl
