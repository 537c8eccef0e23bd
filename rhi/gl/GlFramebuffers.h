// Framebuffer objects by attachment set: made on the first render pass that uses a set, reused by
// every later one, dropped when one of their textures is destroyed.
#pragma once

#include "GlDebugOutput.h"
#include "GlFunctions.h"

#include "rhi/CommandList.h"

#include <cstdint>
#include <map>
#include <vector>

namespace lpv::rhi::gl {

struct GlAttachment {
    GLuint texture = 0;
    bool oneLayer = false; // 3D or array texture: attach one layer / slice, not every one (layered)
    uint32_t mipLevel = 0;
    uint32_t layer = 0;
    bool stencil = false; // a depth format with a stencil: attached as depth and stencil
};

class GlFramebufferCache {
public:
    void init(const Functions& gl, const ObjectLabeler& label);
    void destroy();

    // Throws rhi::Error when the driver calls the set incomplete.
    GLuint get(const GlAttachment* colors, uint32_t colorCount, const GlAttachment* depth, const char* name);
    void forgetTexture(GLuint texture);

private:
    const Functions* gl_ = nullptr;
    const ObjectLabeler* label_ = nullptr;
    // Key: {colorCount | hasDepth << 8, then per attachment: texture name, oneLayer << 63 | mip << 32 |
    // layer}.
    std::map<std::vector<uint64_t>, GLuint> framebuffers_;
    std::vector<uint64_t> key_; // reused: a cache hit allocates nothing
};

} // namespace lpv::rhi::gl
