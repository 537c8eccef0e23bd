// Whole pipeline states, created once and bound as a unit (no GL-style state machine).
#pragma once

#include "rhi/Format.h"
#include "rhi/Resources.h"
#include "rhi/Shader.h"

#include <cstdint>
#include <string>
#include <vector>

namespace lpv::rhi {

enum class VertexFormat : uint8_t { Float1, Float2, Float3, Float4, UByte4Norm, UInt1 };
enum class PrimitiveTopology : uint8_t { TriangleList, TriangleStrip, LineList, PointList };
enum class CullMode : uint8_t { None, Front, Back };
enum class FrontFace : uint8_t { CounterClockwise, Clockwise };
enum class BlendFactor : uint8_t { Zero, One, SrcAlpha, OneMinusSrcAlpha, DstAlpha, OneMinusDstAlpha };
enum class BlendOp : uint8_t { Add, Max };
// What a fragment that passes the stencil and depth tests does to the stencil. Replace writes the
// reference, or the fragment shader's own value where it exports one (Caps::shaderStencilExport:
// gl_FragStencilRefARB).
enum class StencilOp : uint8_t { Keep, Replace };

struct VertexAttribute {
    uint32_t location = 0;
    VertexFormat format = VertexFormat::Float3;
    uint32_t offset = 0;
    uint32_t bufferSlot = 0;
};

struct VertexBufferLayout {
    uint32_t stride = 0;
    bool perInstance = false;
};

struct BlendState {
    bool enabled = false;
    BlendFactor srcColor = BlendFactor::One;
    BlendFactor dstColor = BlendFactor::Zero;
    BlendOp colorOp = BlendOp::Add;
    BlendFactor srcAlpha = BlendFactor::One;
    BlendFactor dstAlpha = BlendFactor::Zero;
    BlendOp alphaOp = BlendOp::Add;

    static BlendState opaque() { return {}; }
    // dst += src: light accumulation and volume injection.
    static BlendState additive() {
        return {true,         BlendFactor::One, BlendFactor::One,
                BlendOp::Add, BlendFactor::One, BlendFactor::One,
                BlendOp::Add};
    }
    static BlendState alpha() {
        return {true,         BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha,
                BlendOp::Add, BlendFactor::One,      BlendFactor::OneMinusSrcAlpha,
                BlendOp::Add};
    }
};

// One state for front and back faces. The test passes where (reference & readMask) compare
// (stencil & readMask) holds, e.g. Equal with a readMask that selects a field of the stencil bits.
// Needs a depth format with a stencil (hasStencil).
struct StencilState {
    bool enabled = false;
    CompareOp compare = CompareOp::Always;
    uint8_t reference = 0;
    uint8_t readMask = 0xff;
    uint8_t writeMask = 0;
    StencilOp pass = StencilOp::Keep; // where both tests pass; failing fragments keep the stencil
};

struct GraphicsPipelineDesc {
    const ShaderBinary* vertex = nullptr;
    const ShaderBinary* fragment = nullptr;
    std::vector<VertexBufferLayout> vertexBuffers;
    std::vector<VertexAttribute> attributes;
    PrimitiveTopology topology = PrimitiveTopology::TriangleList;
    CullMode cull = CullMode::None;
    FrontFace frontFace = FrontFace::CounterClockwise;
    bool depthTest = false;
    bool depthWrite = false;
    CompareOp depthCompare = CompareOp::LessOrEqual;
    float depthBiasConstant = 0.0f; // both zero: no bias
    float depthBiasSlope = 0.0f;
    StencilState stencil;
    std::vector<Format> colorFormats;
    // One entry per color target; a single entry applies to all targets.
    std::vector<BlendState> blend;
    Format depthFormat = Format::Undefined;
    std::string debugName;
};

struct ComputePipelineDesc {
    const ShaderBinary* compute = nullptr;
    std::string debugName;
};

} // namespace lpv::rhi
