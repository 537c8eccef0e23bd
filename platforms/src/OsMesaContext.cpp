// OpenGL 4.5 core through OSMesa (Mesa's off-screen software renderer). It needs a colour buffer
// to be made current; the backend renders into framebuffer objects, so a 1x1 one suffices.
#include "platforms/GlContext.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace lpv::platforms {
namespace {

class OsMesaGlContext final : public GlContext {
public:
    OsMesaGlContext() {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               0,
                               OSMESA_STENCIL_BITS,
                               0,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        context_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!context_) throw std::runtime_error("OSMesaCreateContextAttribs (OpenGL 4.5 core) failed");
        makeCurrent();
    }
    ~OsMesaGlContext() override {
        // Unbind first so no thread state points at the destroyed context when the next device
        // (OSMesa or EGL) is made in this process.
        if (OSMesaGetCurrentContext() == context_) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        OSMesaDestroyContext(context_);
    }
    void makeCurrent() override {
        if (!OSMesaMakeCurrent(context_, pixel_, GL_UNSIGNED_BYTE, 1, 1))
            throw std::runtime_error("OSMesaMakeCurrent failed");
    }
    GlProc getProcAddress(const char* name) override {
        return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
    }
    void swapBuffers() override {}
    bool hasDefaultFramebuffer() const override { return false; }
    const char* platformName() const override { return "osmesa"; }

private:
    OSMesaContext context_ = nullptr;
    unsigned char pixel_[4] = {};
};

} // namespace

// OSMesa makes no distinction for debug contexts; the backend enables GL_DEBUG_OUTPUT itself.
std::unique_ptr<GlContext> createOsMesaContext(bool) {
    return std::make_unique<OsMesaGlContext>();
}

} // namespace lpv::platforms
