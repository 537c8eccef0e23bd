// Pipelines of the GL backend: the SPIRV-Cross GLSL of each stage compiled and linked into one
// program, plus a vertex array object holding the attribute formats. Fixed-function state stays in
// the descriptor and is applied when the pipeline is bound.
#include "GlDevice.h"
#include "GlFormats.h"

#include "../src/DescValidation.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::gl {
namespace {

GLenum shaderType(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::Vertex:
        return GL_VERTEX_SHADER;
    case ShaderStage::Fragment:
        return GL_FRAGMENT_SHADER;
    case ShaderStage::Compute:
        return GL_COMPUTE_SHADER;
    }
    return GL_VERTEX_SHADER;
}

void requireStage(const ShaderBinary& s, ShaderStage stage, const std::string& pipeline, const char* what) {
    if (s.stage != stage)
        throw Error("pipeline '" + pipeline + "': '" + std::string(s.name) + "' is not a " + what +
                    " shader");
    if (s.glsl.empty()) throw Error("pipeline '" + pipeline + "': '" + std::string(s.name) + "' has no GLSL");
}

} // namespace

// A storage image's binding is its image unit. A driver with fewer units than a binding rejects
// the shader when compiling it; this holds a linked program to the device's
// Caps::storageImageBindings as Vulkan pipeline creation does, so a lowered
// DeviceConfig::storageImageBindings catches a shader past it on every backend.
void GlDevice::checkStorageImageUnits(GLuint program, const std::string& name) const {
    GLint uniforms = 0;
    gl_.glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &uniforms);
    for (GLint i = 0; i < uniforms; ++i) {
        const GLenum props[2] = {GL_TYPE, GL_LOCATION};
        GLint values[2] = {0, -1};
        gl_.glGetProgramResourceiv(program, GL_UNIFORM, GLuint(i), 2, props, 2, nullptr, values);
        // GL's image types are one contiguous range of enums.
        const bool image =
            values[0] >= GL_IMAGE_1D && values[0] <= GL_UNSIGNED_INT_IMAGE_2D_MULTISAMPLE_ARRAY;
        if (!image || values[1] < 0) continue;
        GLint unit = 0;
        gl_.glGetUniformiv(program, values[1], &unit);
        validateStorageImageBinding(uint32_t(unit), caps_, "OpenGL: pipeline '" + name + "'");
    }
}

GLuint GlDevice::linkProgram(std::initializer_list<const ShaderBinary*> stages, const std::string& name) {
    const GLuint program = gl_.glCreateProgram();
    GLuint shaders[3] = {};
    uint32_t count = 0;
    auto cleanup = [&] {
        for (uint32_t i = 0; i < count; ++i)
            gl_.glDeleteShader(shaders[i]);
    };
    for (const ShaderBinary* s : stages) {
        const GLuint shader = gl_.glCreateShader(shaderType(s->stage));
        shaders[count++] = shader;
        const GLchar* source = s->glsl.data();
        const GLint length = GLint(s->glsl.size());
        gl_.glShaderSource(shader, 1, &source, &length);
        gl_.glCompileShader(shader);
        GLint ok = 0;
        gl_.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[4096] = {};
            gl_.glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
            cleanup();
            gl_.glDeleteProgram(program);
            throw Error("OpenGL: shader '" + std::string(s->name) + "' of pipeline '" + name +
                        "' does not compile: " + log);
        }
        gl_.glAttachShader(program, shader);
    }
    gl_.glLinkProgram(program);
    cleanup(); // flagged for deletion; freed with the program
    GLint ok = 0;
    gl_.glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        gl_.glGetProgramInfoLog(program, sizeof(log), nullptr, log);
        gl_.glDeleteProgram(program);
        throw Error("OpenGL: pipeline '" + name + "' does not link: " + log);
    }
    try {
        checkStorageImageUnits(program, name);
    } catch (...) {
        gl_.glDeleteProgram(program);
        throw;
    }
    label_(GL_PROGRAM, program, name);
    return program;
}

GraphicsPipelineHandle GlDevice::createPipeline(const GraphicsPipelineDesc& desc) {
    const std::string& name = desc.debugName;
    if (!desc.vertex) throw Error("graphics pipeline '" + name + "': no vertex shader");
    requireStage(*desc.vertex, ShaderStage::Vertex, name, "vertex");
    if (desc.fragment) requireStage(*desc.fragment, ShaderStage::Fragment, name, "fragment");
    if (desc.colorFormats.size() > RenderPassDesc::kMaxColorTargets)
        throw Error("graphics pipeline '" + name + "': more than 8 color targets");
    if (!desc.blend.empty() && desc.blend.size() != 1 && desc.blend.size() != desc.colorFormats.size())
        throw Error("graphics pipeline '" + name + "': blend needs one entry or one per color target");
    if (desc.vertexBuffers.size() > GlCommandList::kMaxVertexBuffers)
        throw Error("graphics pipeline '" + name + "': more than " +
                    std::to_string(GlCommandList::kMaxVertexBuffers) + " vertex buffers");
    validateStencilState(desc);
    for (const VertexAttribute& a : desc.attributes)
        if (a.bufferSlot >= desc.vertexBuffers.size())
            throw Error("graphics pipeline '" + name + "': attribute " + std::to_string(a.location) +
                        " uses vertex buffer slot " + std::to_string(a.bufferSlot) + " with no layout");

    GlGraphicsPipeline p;
    p.desc = desc;
    p.program =
        desc.fragment ? linkProgram({desc.vertex, desc.fragment}, name) : linkProgram({desc.vertex}, name);
    // SPIRV-Cross turns gl_InstanceIndex into gl_InstanceID + this uniform on GL (no base instance
    // in GLSL 4.50); it is set per draw.
    p.baseInstanceLocation = gl_.glGetUniformLocation(p.program, "SPIRV_Cross_BaseInstance");
    p.bindings = reflectShaderBindings(*desc.vertex, caps_);
    if (desc.fragment) mergeShaderBindings(p.bindings, reflectShaderBindings(*desc.fragment, caps_), name);
    gl_.glCreateVertexArrays(1, &p.vao);
    for (const VertexAttribute& a : desc.attributes) {
        const GlVertexFormat f = vertexFormat(a.format);
        gl_.glEnableVertexArrayAttrib(p.vao, a.location);
        if (f.integer)
            gl_.glVertexArrayAttribIFormat(p.vao, a.location, f.size, f.type, a.offset);
        else
            gl_.glVertexArrayAttribFormat(p.vao, a.location, f.size, f.type, f.normalized, a.offset);
        gl_.glVertexArrayAttribBinding(p.vao, a.location, a.bufferSlot);
    }
    for (size_t i = 0; i < desc.vertexBuffers.size(); ++i)
        gl_.glVertexArrayBindingDivisor(p.vao, GLuint(i), desc.vertexBuffers[i].perInstance ? 1 : 0);
    label_(GL_VERTEX_ARRAY, p.vao, name);
    return graphicsPipelines.insert(std::move(p));
}

ComputePipelineHandle GlDevice::createPipeline(const ComputePipelineDesc& desc) {
    if (!desc.compute) throw Error("compute pipeline '" + desc.debugName + "': no compute shader");
    requireStage(*desc.compute, ShaderStage::Compute, desc.debugName, "compute");
    std::vector<ShaderBinding> bindings = reflectShaderBindings(*desc.compute, caps_);
    return computePipelines.insert(
        {desc.debugName, linkProgram({desc.compute}, desc.debugName), std::move(bindings)});
}

void GlDevice::destroy(GraphicsPipelineHandle h) {
    GlGraphicsPipeline p = graphicsPipelines.remove(h);
    gl_.glDeleteProgram(p.program);
    gl_.glDeleteVertexArrays(1, &p.vao);
}

void GlDevice::destroy(ComputePipelineHandle h) {
    GlComputePipeline p = computePipelines.remove(h);
    gl_.glDeleteProgram(p.program);
}

} // namespace lpv::rhi::gl
