// The platform the game runs on, behind one interface: headless (the GPU context comes from EGL
// surfaceless or OSMesa, see GlContext.h; Vulkan needs nothing) or windowed (GLFW on X11). Events,
// input, the clock and file access look the same on both; headless simply has no input. Either
// asks to quit on SIGINT (Ctrl+C) or SIGTERM: the platform catches the first of them for the game
// to end its run and write its outputs; a second one 0.3 s or more later ends the process as it
// would have.
// The game asks for a platform and does not branch on which one it got.
#pragma once

#include "platforms/Window.h"

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace lpv::platforms {

class Platform {
public:
    // Windowed when `wantWindow` and an X display is reachable, headless otherwise; then
    // windowError() says why for the caller to report (or refuse).
    static std::unique_ptr<Platform> create(bool wantWindow, const WindowDesc& window);
    ~Platform();

    const char* name() const { return window_ ? "windowed (GLFW)" : "headless"; }
    // The window for the device to present to; null when headless.
    Window* window() { return window_.get(); }
    // Why a window that was wanted could not open (GLFW's error); empty otherwise.
    const std::string& windowError() const { return windowError_; }

    // See Window::pollEvents; headless never waits.
    void pollEvents(double waitSeconds = 0.0);
    // The window closed, Esc, or a SIGINT or SIGTERM (then quitSignalName() names it).
    bool quitRequested() const;
    const char* quitSignalName() const; // null when no signal asked to quit
    bool keyDown(int key) const;
    bool keyPressed(int key) const;
    void cursorDelta(double& dx, double& dy) const;
    // The size frames should be rendered at (the window's framebuffer, or the requested size).
    void frameSize(uint32_t& width, uint32_t& height) const;

    uint64_t nowNanoseconds() const;
    // Whole-file access; throws std::runtime_error naming the path and the reason.
    static std::string readFile(const std::string& path);
    // The same without throwing: 0, or the errno of what failed. A path that opens but cannot be
    // read (a directory, /proc/self/mem) fails too, rather than reading as an empty file.
    static int tryReadFile(const std::string& path, std::string& contents);
    // Flush and close errors count as failures (a full disk shows there, not at fwrite).
    static void writeFile(const std::string& path, std::string_view contents);
    // Creates `directory` and its parents where missing; throws std::runtime_error with the reason.
    static void createDirectories(const std::string& directory);
    // For a file written at the end of a long run, checked before it starts: creates the file's
    // folder and opens the file for writing (a file made for the check is removed again, one that
    // was there is left unchanged). Throws std::runtime_error naming the path and the reason.
    static void checkWritable(const std::string& path);

private:
    explicit Platform(std::unique_ptr<Window> window, const WindowDesc& desc);
    std::unique_ptr<Window> window_;
    WindowDesc desc_;
    std::string windowError_;
};

} // namespace lpv::platforms
