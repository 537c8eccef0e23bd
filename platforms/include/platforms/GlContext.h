// An OpenGL 4.5 core context, from whichever platform provides one: EGL's surfaceless platform or
// OSMesa when headless, GLFW with a window. The GL backend loads every entry point through
// getProcAddress() (never by linking libGL: linking libGL and libOSMesa together breaks one).
#pragma once

#include <memory>

namespace lpv::platforms {

class Window;

using GlProc = void (*)();

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual void makeCurrent() = 0;
    virtual GlProc getProcAddress(const char* name) = 0;
    // Presents the default framebuffer (windowed only; a no-op headless).
    virtual void swapBuffers() = 0;
    virtual bool hasDefaultFramebuffer() const = 0;
    virtual const char* platformName() const = 0;
};

// Each throws std::runtime_error with the platform's reason when no 4.5 core context can be made.
std::unique_ptr<GlContext> createEglSurfacelessContext(bool debug);
std::unique_ptr<GlContext> createOsMesaContext(bool debug);
std::unique_ptr<GlContext> createWindowGlContext(Window& window, bool debug);

} // namespace lpv::platforms
