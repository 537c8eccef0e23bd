// What the GL backend keeps per RHI object: the descriptor it was made from and the GL names.
#pragma once

#include "../src/ShaderBindings.h"

#include "rhi/Pipeline.h"
#include "rhi/Resources.h"

#include <GL/glcorearb.h>

#include <cstdint>
#include <string>
#include <vector>

namespace lpv::rhi::gl {

struct GlBuffer {
    BufferDesc desc;
    GLuint id = 0;
    void* mapped = nullptr; // MemoryAccess::HostWrite or HostRead: persistent, coherent mapping
};

struct GlTexture {
    TextureDesc desc;
    GLuint id = 0;
    GLenum target = 0;

    uint32_t width(uint32_t mip) const { return desc.width > (1u << mip) ? desc.width >> mip : 1u; }
    uint32_t height(uint32_t mip) const { return desc.height > (1u << mip) ? desc.height >> mip : 1u; }
    // Slices of a 3D texture shrink with the mip; array layers do not.
    uint32_t depthOrLayers(uint32_t mip) const {
        if (desc.kind != TextureKind::Tex3D) return desc.depthOrLayers;
        return desc.depthOrLayers > (1u << mip) ? desc.depthOrLayers >> mip : 1u;
    }
    uint64_t mipBytes(uint32_t mip) const {
        return uint64_t(width(mip)) * height(mip) * depthOrLayers(mip) * bytesPerPixel(desc.format);
    }
};

struct GlSampler {
    SamplerDesc desc;
    GLuint id = 0;
};

struct GlGraphicsPipeline {
    GraphicsPipelineDesc desc;
    GLuint program = 0;
    GLuint vao = 0;                      // attribute formats; buffers are attached per draw
    GLint baseInstanceLocation = -1;     // SPIRV-Cross's stand-in for gl_InstanceIndex's base
    std::vector<ShaderBinding> bindings; // both stages': what a draw reads and writes
};

struct GlComputePipeline {
    std::string name;
    GLuint program = 0;
    std::vector<ShaderBinding> bindings; // what a dispatch reads and writes
};

} // namespace lpv::rhi::gl
