// KHR_debug message forwarding and object labels.
#include "GlDebugOutput.h"

#include "platforms/Log.h"

#include <algorithm>
#include <string>

namespace lpv::rhi::gl {
namespace {

// The contract: GL_DEBUG_TYPE_ERROR is an error; anything else of high or medium severity is a
// warning; low severity and notifications (shader recompiles, buffer placement hints) are noise.
void APIENTRY onGlDebugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei length,
                               const GLchar* message, const void* user) {
    DebugMessage m;
    if (type == GL_DEBUG_TYPE_ERROR)
        m.severity = DebugSeverity::Error;
    else if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM)
        m.severity = DebugSeverity::Warning;
    else
        return;
    m.text = "GL: ";
    m.text += length >= 0 ? std::string(message, size_t(length)) : std::string(message);
    const auto* config = static_cast<const DeviceConfig*>(user);
    if (config->onDebugMessage)
        config->onDebugMessage(m);
    else if (m.severity == DebugSeverity::Error)
        log::error(m.text);
    else
        log::warn(m.text);
}

} // namespace

void installDebugOutput(const Functions& gl, const DeviceConfig& config) {
    gl.glEnable(GL_DEBUG_OUTPUT);
    gl.glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    gl.glDebugMessageCallback(onGlDebugMessage, &config);
    gl.glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

void uninstallDebugOutput(const Functions& gl) {
    gl.glDebugMessageCallback(nullptr, nullptr);
    gl.glDisable(GL_DEBUG_OUTPUT);
}

void ObjectLabeler::init(const Functions& gl) {
    gl_ = &gl;
    GLint max = 0;
    gl.glGetIntegerv(GL_MAX_LABEL_LENGTH, &max);
    if (max > 0) maxLength_ = max;
}

void ObjectLabeler::operator()(GLenum type, GLuint id, std::string_view name) const {
    if (name.empty() || !gl_) return;
    const GLsizei length = GLsizei(std::min<size_t>(name.size(), size_t(maxLength_ - 1)));
    gl_->glObjectLabel(type, id, length, name.data());
}

} // namespace lpv::rhi::gl
