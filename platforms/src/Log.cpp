// The process-wide log sink.
#include "platforms/Log.h"

#include <cstdio>
#include <mutex>
#include <string>

namespace lpv::log {
namespace {
std::mutex gMutex;
Sink gSink;

const char* levelName(Level l) {
    switch (l) {
    case Level::Debug:
        return "debug";
    case Level::Info:
        return "info";
    case Level::Warning:
        return "warning";
    case Level::Error:
        return "error";
    }
    return "?";
}
} // namespace

Sink setSink(Sink sink) {
    std::lock_guard lock(gMutex);
    std::swap(gSink, sink);
    return sink;
}

void write(Level level, std::string_view message) {
    std::lock_guard lock(gMutex);
    if (gSink) {
        gSink(level, message);
        return;
    }
    std::fprintf(stderr, "[%s] %.*s\n", levelName(level), int(message.size()), message.data());
}

} // namespace lpv::log
