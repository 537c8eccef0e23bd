// OpenGL 4.5 core through EGL's surfaceless platform (Mesa): no display and no window needed;
// rendering goes to framebuffer objects.
#include "platforms/GlContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace lpv::platforms {
namespace {

std::string eglErrorName(EGLint e) {
    switch (e) {
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    default:
        return "EGL error 0x" + std::to_string(e);
    }
}

class EglSurfacelessContext final : public GlContext {
public:
    explicit EglSurfacelessContext(bool debug) {
        const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        if (!clientExtensions || !std::strstr(clientExtensions, "EGL_MESA_platform_surfaceless"))
            throw std::runtime_error(
                "EGL has no surfaceless platform (EGL_MESA_platform_surfaceless; Mesa's libegl-mesa0)");
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (!getPlatformDisplay) throw std::runtime_error("eglGetPlatformDisplayEXT is missing");
        display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display_ == EGL_NO_DISPLAY)
            throw std::runtime_error("eglGetPlatformDisplayEXT(surfaceless) failed: " +
                                     eglErrorName(eglGetError()));
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display_, &major, &minor))
            throw std::runtime_error("eglInitialize failed: " + eglErrorName(eglGetError()));
        ++initializedCount_;
        try {
            createContext(debug);
        } catch (...) {
            release();
            throw;
        }
    }
    ~EglSurfacelessContext() override { release(); }

    void makeCurrent() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw std::runtime_error("eglMakeCurrent failed: " + eglErrorName(eglGetError()));
    }
    GlProc getProcAddress(const char* name) override {
        return reinterpret_cast<GlProc>(eglGetProcAddress(name));
    }
    void swapBuffers() override {}
    bool hasDefaultFramebuffer() const override { return false; }
    const char* platformName() const override { return "egl-surfaceless"; }

private:
    void createContext(bool debug) {
        if (!eglBindAPI(EGL_OPENGL_API))
            throw std::runtime_error("eglBindAPI(EGL_OPENGL_API) failed: " + eglErrorName(eglGetError()));
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                  4,
                                  EGL_CONTEXT_MINOR_VERSION,
                                  5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG,
                                  debug ? EGL_TRUE : EGL_FALSE,
                                  EGL_NONE};
        // No config: the context only ever renders into framebuffer objects (EGL_KHR_no_config_context).
        // Without that extension any config that can make OpenGL contexts does.
        EGLConfig config = EGL_NO_CONFIG_KHR;
        const char* displayExtensions = eglQueryString(display_, EGL_EXTENSIONS);
        if (!displayExtensions || !std::strstr(displayExtensions, "EGL_KHR_no_config_context")) {
            const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (!eglChooseConfig(display_, want, &config, 1, &count) || count == 0)
                throw std::runtime_error(
                    "eglChooseConfig found no OpenGL config (and no EGL_KHR_no_config_context)");
        }
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attribs);
        if (context_ == EGL_NO_CONTEXT)
            throw std::runtime_error("eglCreateContext (OpenGL 4.5 core) failed: " +
                                     eglErrorName(eglGetError()));
        makeCurrent();
    }

    void release() {
        if (context_ != EGL_NO_CONTEXT) {
            if (eglGetCurrentContext() == context_)
                eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(display_, context_);
            context_ = EGL_NO_CONTEXT;
        }
        // The surfaceless display is one per process: terminate it only when its last context goes,
        // so a second device made before the first is destroyed keeps working.
        if (--initializedCount_ == 0) eglTerminate(display_);
    }

    static inline int initializedCount_ = 0;
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

} // namespace

std::unique_ptr<GlContext> createEglSurfacelessContext(bool debug) {
    return std::make_unique<EglSurfacelessContext>(debug);
}

} // namespace lpv::platforms
