#include "engine/config/EmptyOptionValue.h"

#include <string_view>

namespace lpv::engine {

std::optional<std::string> findEmptyOptionValue(std::span<char* const> args) {
    for (const char* arg : args) {
        const std::string_view a(arg);
        if (a == "--") break;
        if (a.size() > 3 && a.starts_with("--") && a.ends_with('=') && a.find('=') == a.size() - 1)
            return std::string(a);
    }
    return std::nullopt;
}

} // namespace lpv::engine
