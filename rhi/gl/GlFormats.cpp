// Format and state tables.
#include "GlFormats.h"

#include "rhi/Error.h"

namespace lpv::rhi::gl {

GlFormat glFormat(Format f) {
    switch (f) {
    case Format::RGBA8Unorm:
        return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::RGBA8Srgb:
        return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::RGBA16F:
        return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT};
    case Format::RGBA32F:
        return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case Format::RG16F:
        return {GL_RG16F, GL_RG, GL_HALF_FLOAT};
    case Format::R32F:
        return {GL_R32F, GL_RED, GL_FLOAT};
    case Format::R32UI:
        return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
    case Format::RG32UI:
        return {GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT};
    case Format::RGBA32UI:
        return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT};
    case Format::D32F:
        return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    case Format::D32FS8:
        return {GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV};
    case Format::Undefined:
        break;
    }
    throw Error("OpenGL: no format for " + std::string(formatName(f)));
}

GLenum textureTarget(TextureKind k) {
    switch (k) {
    case TextureKind::Tex2D:
        return GL_TEXTURE_2D;
    case TextureKind::Tex2DArray:
        return GL_TEXTURE_2D_ARRAY;
    case TextureKind::Tex3D:
        return GL_TEXTURE_3D;
    }
    return GL_TEXTURE_2D;
}

GLenum compareFunc(CompareOp op) {
    switch (op) {
    case CompareOp::Never:
        return GL_NEVER;
    case CompareOp::Less:
        return GL_LESS;
    case CompareOp::LessOrEqual:
        return GL_LEQUAL;
    case CompareOp::Greater:
        return GL_GREATER;
    case CompareOp::GreaterOrEqual:
        return GL_GEQUAL;
    case CompareOp::Equal:
        return GL_EQUAL;
    case CompareOp::Always:
        return GL_ALWAYS;
    }
    return GL_LESS;
}

GLenum blendFactor(BlendFactor f) {
    switch (f) {
    case BlendFactor::Zero:
        return GL_ZERO;
    case BlendFactor::One:
        return GL_ONE;
    case BlendFactor::SrcAlpha:
        return GL_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha:
        return GL_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstAlpha:
        return GL_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha:
        return GL_ONE_MINUS_DST_ALPHA;
    }
    return GL_ONE;
}

GLenum blendOp(BlendOp op) {
    return op == BlendOp::Max ? GL_MAX : GL_FUNC_ADD;
}

GLenum addressMode(AddressMode m) {
    switch (m) {
    case AddressMode::ClampToEdge:
        return GL_CLAMP_TO_EDGE;
    case AddressMode::Repeat:
        return GL_REPEAT;
    case AddressMode::ClampToBorderWhite:
        return GL_CLAMP_TO_BORDER;
    }
    return GL_CLAMP_TO_EDGE;
}

GLenum primitiveMode(PrimitiveTopology t) {
    switch (t) {
    case PrimitiveTopology::TriangleList:
        return GL_TRIANGLES;
    case PrimitiveTopology::TriangleStrip:
        return GL_TRIANGLE_STRIP;
    case PrimitiveTopology::LineList:
        return GL_LINES;
    case PrimitiveTopology::PointList:
        return GL_POINTS;
    }
    return GL_TRIANGLES;
}

GlVertexFormat vertexFormat(VertexFormat f) {
    switch (f) {
    case VertexFormat::Float1:
        return {1, GL_FLOAT, GL_FALSE};
    case VertexFormat::Float2:
        return {2, GL_FLOAT, GL_FALSE};
    case VertexFormat::Float3:
        return {3, GL_FLOAT, GL_FALSE};
    case VertexFormat::Float4:
        return {4, GL_FLOAT, GL_FALSE};
    case VertexFormat::UByte4Norm:
        return {4, GL_UNSIGNED_BYTE, GL_TRUE};
    case VertexFormat::UInt1:
        return {1, GL_UNSIGNED_INT, GL_FALSE, true};
    }
    return {4, GL_FLOAT, GL_FALSE};
}

} // namespace lpv::rhi::gl
