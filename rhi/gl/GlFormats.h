// RHI formats and states as OpenGL enums.
#pragma once

#include "rhi/Format.h"
#include "rhi/Pipeline.h"
#include "rhi/Resources.h"

#include <GL/glcorearb.h>

namespace lpv::rhi::gl {

struct GlFormat {
    GLenum internal; // storage format
    GLenum format;   // pixel transfer format
    GLenum type;     // pixel transfer type
};

GlFormat glFormat(Format f);
GLenum textureTarget(TextureKind k);
GLenum compareFunc(CompareOp op);
GLenum blendFactor(BlendFactor f);
GLenum blendOp(BlendOp op);
GLenum addressMode(AddressMode m);
GLenum primitiveMode(PrimitiveTopology t);

struct GlVertexFormat {
    GLint size;
    GLenum type;
    GLboolean normalized;
    bool integer = false; // read as an integer (glVertexArrayAttribIFormat)
};
GlVertexFormat vertexFormat(VertexFormat f);

} // namespace lpv::rhi::gl
