// How text from an input file - a value, a key, a name - is echoed in an error or a warning: whole
// when short, else its start and its length, so that a 1 MB string still makes a one-line message.
// Config and glTF errors both cut here.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace lpv::engine {

inline constexpr size_t kShownTextBytes = 80;

// `text` when it has at most `limit` bytes, else its first `limit` bytes (fewer where that would split
// a UTF-8 sequence) and "... (N bytes)".
std::string shownText(std::string_view text, size_t limit = kShownTextBytes);

} // namespace lpv::engine
