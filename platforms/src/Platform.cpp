// Headless and windowed platforms behind one class.
#include "platforms/Platform.h"

#include "platforms/Clock.h"

#include <GLFW/glfw3.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace lpv::platforms {
namespace {

// The signal that asked to quit, 0 until one did, and when (monotonic nanoseconds; 0 until
// stored). Lock-free atomics: a handler may run on any of the process's threads.
std::atomic<int> quitSignal{0};
std::atomic<int64_t> quitSignalNs{0};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<int64_t>::is_always_lock_free);

// The actions the platform replaced, put back when it goes.
struct sigaction previousInt {
}, previousTerm{};

// Records the first signal. A second one 0.3 s or more later ends the process as the signal would
// have, for a run that does not come to an end; one sooner is the same request delivered twice
// (`timeout` signals its child and then its process group). Only async-signal-safe calls here:
// clock_gettime, signal, raise, lock-free atomics.
extern "C" void recordQuitSignal(int signal) {
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const int64_t ns = int64_t(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
    int none = 0;
    if (quitSignal.compare_exchange_strong(none, signal)) {
        quitSignalNs.store(ns);
        return;
    }
    const int64_t first = quitSignalNs.load();
    if (first != 0 && ns - first >= 300'000'000) {
        std::signal(signal, SIG_DFL);
        std::raise(signal);
    }
}

// Catches `signal`, even where the process started ignoring it (a background job of a script
// ignores SIGINT): Ctrl+C in the game's own terminal is what it is for, and `timeout -s INT` too.
void catchQuitSignal(int signal, struct sigaction& previous) {
    struct sigaction action {};
    action.sa_handler = recordQuitSignal;
    sigemptyset(&action.sa_mask);
    sigaction(signal, &action, &previous);
}

} // namespace

std::unique_ptr<Platform> Platform::create(bool wantWindow, const WindowDesc& desc) {
    std::unique_ptr<Window> window;
    if (wantWindow && Window::displayAvailable()) window = std::make_unique<Window>(desc);
    std::unique_ptr<Platform> platform(new Platform(std::move(window), desc));
    if (wantWindow && !platform->window_) platform->windowError_ = Window::displayError();
    return platform;
}

Platform::Platform(std::unique_ptr<Window> window, const WindowDesc& desc)
    : window_(std::move(window)), desc_(desc) {
    quitSignal = 0;
    quitSignalNs = 0;
    catchQuitSignal(SIGINT, previousInt);
    catchQuitSignal(SIGTERM, previousTerm);
}

Platform::~Platform() {
    sigaction(SIGINT, &previousInt, nullptr);
    sigaction(SIGTERM, &previousTerm, nullptr);
}

void Platform::pollEvents(double waitSeconds) {
    if (window_) window_->pollEvents(waitSeconds);
}

bool Platform::quitRequested() const {
    return quitSignal != 0 || (window_ && (window_->shouldClose() || window_->keyPressed(GLFW_KEY_ESCAPE)));
}

const char* Platform::quitSignalName() const {
    return quitSignal == SIGINT ? "SIGINT" : quitSignal == SIGTERM ? "SIGTERM" : nullptr;
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

int Platform::tryReadFile(const std::string& path, std::string& contents) {
    // stdio rather than iostreams: a stream reading a directory just ends, with no errno to tell.
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return errno ? errno : EIO;
    contents.clear();
    char buffer[65536];
    size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0)
        contents.append(buffer, n);
    const int error = std::ferror(f) ? (errno ? errno : EIO) : 0;
    std::fclose(f);
    if (error) contents.clear();
    return error;
}

std::string Platform::readFile(const std::string& path) {
    std::string contents;
    if (const int error = tryReadFile(path, contents))
        throw std::runtime_error("cannot read " + path + ": " + std::strerror(error));
    return contents;
}

void Platform::writeFile(const std::string& path, std::string_view contents) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    // A full disk often shows only when the buffer is flushed or the file closed, so both count.
    errno = 0;
    const bool written =
        std::fwrite(contents.data(), 1, contents.size(), f) == contents.size() && std::fflush(f) == 0;
    const int writeError = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed) {
        const int error = !written ? writeError : errno;
        throw std::runtime_error("cannot write " + path + ": " +
                                 (error ? std::strerror(error) : "write failed"));
    }
}

void Platform::createDirectories(const std::string& directory) {
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (ec) throw std::runtime_error("cannot create directory " + directory + ": " + ec.message());
}

void Platform::checkWritable(const std::string& path) {
    const std::filesystem::path file(path);
    if (file.has_parent_path()) createDirectories(file.parent_path().string());
    std::error_code ec;
    const bool existed = std::filesystem::exists(std::filesystem::symlink_status(file, ec));
    // O_NONBLOCK: a FIFO without a reader fails instead of blocking. O_EXCL: the file removed below
    // is the one made here.
    const int fd = existed ? ::open(path.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC)
                           : ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    ::close(fd);
    if (!existed) ::unlink(path.c_str());
}

} // namespace lpv::platforms
