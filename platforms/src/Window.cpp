// GLFW windows. GLFW is initialised once per process, on first use, and only where a display is
// reachable; headless runs never touch it.
#include "platforms/Window.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <mutex>
#include <stdexcept>
#include <string>

namespace lpv::platforms {
namespace {

std::string gGlfwError;

bool initGlfw() {
    static std::once_flag once;
    static bool ok = false;
    std::call_once(once, [] {
        glfwSetErrorCallback([](int, const char* text) { gGlfwError = text ? text : "unknown GLFW error"; });
        ok = glfwInit() == GLFW_TRUE;
    });
    return ok;
}

} // namespace

bool Window::displayAvailable() {
    return initGlfw();
}

bool Window::displayConfigured() {
    const auto set = [](const char* name) {
        const char* v = std::getenv(name);
        return v && *v;
    };
    return set("DISPLAY") || set("WAYLAND_DISPLAY");
}

std::string Window::displayError() {
    if (initGlfw()) return {};
    return gGlfwError.empty() ? "GLFW could not start" : gGlfwError;
}

Window::Window(const WindowDesc& desc) : desc_(desc) {
    if (!initGlfw()) throw std::runtime_error("cannot open a window: " + gGlfwError);
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
}

GLFWwindow* Window::native(WindowApi api, bool glDebug) {
    if (window_ && api_ == api) return window_;
    if (window_) glfwDestroyWindow(window_);
    window_ = nullptr;
    api_ = api;
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_VISIBLE, desc_.visible ? GLFW_TRUE : GLFW_FALSE);
    if (api == WindowApi::OpenGL) {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, glDebug ? GLFW_TRUE : GLFW_FALSE);
    } else {
        glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    }
    gGlfwError.clear();
    window_ = glfwCreateWindow(int(desc_.width), int(desc_.height), desc_.title.c_str(), nullptr, nullptr);
    if (!window_) throw std::runtime_error("glfwCreateWindow failed: " + gGlfwError);
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
        auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        if (action == GLFW_PRESS && key >= 0 && key < kMaxKeys) self->pressed_[key] = true;
    });
    return window_;
}

void Window::framebufferSize(uint32_t& width, uint32_t& height) const {
    int w = 0, h = 0;
    if (window_) glfwGetFramebufferSize(window_, &w, &h);
    width = uint32_t(w > 0 ? w : 0);
    height = uint32_t(h > 0 ? h : 0);
}

bool Window::shouldClose() const {
    return window_ && glfwWindowShouldClose(window_);
}

void Window::pollEvents(double waitSeconds) {
    std::fill(std::begin(pressed_), std::end(pressed_), false);
    if (waitSeconds > 0.0)
        glfwWaitEventsTimeout(waitSeconds);
    else
        glfwPollEvents();
    dx_ = dy_ = 0;
    if (!window_) return;
    double x = 0, y = 0;
    glfwGetCursorPos(window_, &x, &y);
    const bool held = glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (held && tracking_) {
        dx_ = x - lastX_;
        dy_ = y - lastY_;
    }
    tracking_ = held;
    lastX_ = x;
    lastY_ = y;
}

bool Window::keyDown(int key) const {
    return window_ && glfwGetKey(window_, key) == GLFW_PRESS;
}

bool Window::keyPressed(int key) const {
    return key >= 0 && key < kMaxKeys && pressed_[key];
}

void Window::cursorDelta(double& dx, double& dy) const {
    dx = dx_;
    dy = dy_;
}

} // namespace lpv::platforms
