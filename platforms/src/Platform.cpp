// Headless and windowed platforms behind one class.
#include "platforms/Platform.h"

#include "platforms/Clock.h"

#include <GLFW/glfw3.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace lpv::platforms {

std::unique_ptr<Platform> Platform::create(bool wantWindow, const WindowDesc& desc) {
    std::unique_ptr<Window> window;
    if (wantWindow && Window::displayAvailable()) window = std::make_unique<Window>(desc);
    return std::unique_ptr<Platform>(new Platform(std::move(window), desc));
}

Platform::Platform(std::unique_ptr<Window> window, const WindowDesc& desc)
    : window_(std::move(window)), desc_(desc) {}

Platform::~Platform() = default;

void Platform::pollEvents() {
    if (window_) window_->pollEvents();
}

bool Platform::quitRequested() const {
    return window_ && (window_->shouldClose() || window_->keyPressed(GLFW_KEY_ESCAPE));
}

bool Platform::keyDown(int key) const {
    return window_ && window_->keyDown(key);
}

bool Platform::keyPressed(int key) const {
    return window_ && window_->keyPressed(key);
}

void Platform::cursorDelta(double& dx, double& dy) const {
    dx = dy = 0;
    if (window_) window_->cursorDelta(dx, dy);
}

void Platform::frameSize(uint32_t& width, uint32_t& height) const {
    width = desc_.width;
    height = desc_.height;
    if (window_) window_->framebufferSize(width, height);
}

uint64_t Platform::nowNanoseconds() const {
    return platforms::nowNanoseconds();
}

std::string Platform::readFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void Platform::writeFile(const std::string& path, const std::string& contents) {
    std::ofstream out(path, std::ios::binary);
    out << contents;
    if (!out) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

} // namespace lpv::platforms
