// TEMPORARY: replaced by the GL context implementation.
#include "platforms/GlContext.h"
#include <stdexcept>
namespace lpv::platforms {
std::unique_ptr<GlContext> createEglSurfacelessContext(bool) { throw std::runtime_error("not built"); }
}
