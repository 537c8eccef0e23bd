#include "engine/config/EmptyOptionValue.h"

#include <cstdio>
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

bool refuseEmptyOptionValue(int argc, char** argv) {
    const auto empty = findEmptyOptionValue({argv + 1, argv + argc});
    if (empty)
        std::fprintf(stderr, "error: %s: expected a value after '='\nRun with --help for more information.\n",
                     empty->c_str());
    return empty.has_value();
}

} // namespace lpv::engine
