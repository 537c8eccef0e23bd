// The per-frame ring behind CommandList::pushUniforms: one persistently mapped buffer made at
// device creation with one region of DeviceConfig::uniformRingBytes per frame in flight. A push is
// a memcpy and a glBindBufferRange; the region is reused only after the frame fence that guards
// it has signalled, so the GPU never reads bytes the CPU is overwriting.
#pragma once

#include "GlFunctions.h"

#include <cstdint>

namespace lpv::rhi::gl {

class GlUniformRing {
public:
    void create(const Functions& gl, uint64_t regionBytes, uint32_t regions);
    void destroy();

    void beginFrame(uint32_t region);
    // Copies `data` into this frame's region and returns its offset in buffer().
    uint64_t push(const void* data, uint32_t size);

    GLuint buffer() const { return buffer_; }
    uint64_t totalBytes() const { return regionBytes_ * regions_; }

private:
    const Functions* gl_ = nullptr;
    GLuint buffer_ = 0;
    std::byte* mapped_ = nullptr;
    uint64_t regionBytes_ = 0;
    uint32_t regions_ = 0;
    uint64_t alignment_ = 256;
    uint64_t base_ = 0;
    uint64_t cursor_ = 0;
};

} // namespace lpv::rhi::gl
