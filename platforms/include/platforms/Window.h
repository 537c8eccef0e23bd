// A desktop window (GLFW on X11) with its input events. The native window is made lazily for the
// graphics API the device picks, because a GL window carries a context and a Vulkan one must not.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

struct GLFWwindow;

namespace lpv::platforms {

enum class WindowApi { OpenGL, Vulkan };

struct WindowDesc {
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string title = "LPV Engine";
    bool visible = true;
};

class Window {
public:
    // Throws std::runtime_error when no display is available.
    explicit Window(const WindowDesc& desc);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // Creates (or re-creates for another API) the native window. For OpenGL it holds a 4.5 core
    // context; for Vulkan it has none.
    GLFWwindow* native(WindowApi api, bool glDebug = false);
    GLFWwindow* native() const { return window_; }

    void framebufferSize(uint32_t& width, uint32_t& height) const;
    bool shouldClose() const;
    // With `waitSeconds` > 0, sleeps until an event arrives or that time passes (a minimised
    // window has nothing to draw, and spinning would take a core).
    void pollEvents(double waitSeconds = 0.0);
    // Input, polled: a key by its GLFW_KEY_* code, keys pressed since the last pollEvents() (for
    // toggles), and the cursor movement since the last pollEvents() while the right button is held.
    bool keyDown(int key) const;
    bool keyPressed(int key) const;
    void cursorDelta(double& dx, double& dy) const;
    static bool displayAvailable();
    // Whether a display is named at all (DISPLAY or WAYLAND_DISPLAY set), reachable or not.
    static bool displayConfigured();
    // Why displayAvailable() is false: GLFW's error ("X11: Failed to open display :1").
    static std::string displayError();

private:
    WindowDesc desc_;
    GLFWwindow* window_ = nullptr;
    WindowApi api_ = WindowApi::Vulkan;
    static constexpr int kMaxKeys = 512;
    bool pressed_[kMaxKeys] = {};
    double lastX_ = 0, lastY_ = 0, dx_ = 0, dy_ = 0;
    bool tracking_ = false;
};

} // namespace lpv::platforms
