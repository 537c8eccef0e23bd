// One log for every layer. Lines go to stderr unless a sink is installed (tests capture them).
#pragma once

#include <functional>
#include <string_view>

namespace lpv::log {

enum class Level { Debug, Info, Warning, Error };

using Sink = std::function<void(Level, std::string_view)>;
// Returns the previous sink; an empty sink restores stderr.
Sink setSink(Sink sink);
void write(Level level, std::string_view message);

inline void debug(std::string_view m) {
    write(Level::Debug, m);
}
inline void info(std::string_view m) {
    write(Level::Info, m);
}
inline void warn(std::string_view m) {
    write(Level::Warning, m);
}
inline void error(std::string_view m) {
    write(Level::Error, m);
}

} // namespace lpv::log
