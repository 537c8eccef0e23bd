// Loading the GL entry points from the current context.
#include "GlFunctions.h"

#include "rhi/Error.h"

#include <string>

namespace lpv::rhi::gl {

void Functions::load(platforms::GlContext& context) {
#define LPV_GL_LOAD(type, name)                                                                              \
    name = reinterpret_cast<type>(context.getProcAddress(#name));                                            \
    if (!name) throw BackendUnavailable(std::string("OpenGL entry point ") + #name + " is missing");
    LPV_GL_FUNCTIONS(LPV_GL_LOAD)
#undef LPV_GL_LOAD
}

} // namespace lpv::rhi::gl
