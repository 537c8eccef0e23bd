// OpenGL 4.5 core in a GLFW window; presents with glfwSwapBuffers.
#include "platforms/GlContext.h"
#include "platforms/Window.h"

#include <GLFW/glfw3.h>

namespace lpv::platforms {
namespace {

class WindowGlContext final : public GlContext {
public:
    WindowGlContext(Window& window, bool debug) : window_(window.native(WindowApi::OpenGL, debug)) {
        makeCurrent();
        glfwSwapInterval(0); // the frame loop is paced by the game, not by vsync
    }
    ~WindowGlContext() override { glfwMakeContextCurrent(nullptr); }
    void makeCurrent() override { glfwMakeContextCurrent(window_); }
    GlProc getProcAddress(const char* name) override { return glfwGetProcAddress(name); }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    bool hasDefaultFramebuffer() const override { return true; }
    const char* platformName() const override { return "glfw"; }

private:
    GLFWwindow* window_;
};

} // namespace

std::unique_ptr<GlContext> createWindowGlContext(Window& window, bool debug) {
    return std::make_unique<WindowGlContext>(window, debug);
}

} // namespace lpv::platforms
