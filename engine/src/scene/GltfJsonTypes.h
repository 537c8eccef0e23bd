// The glTF file's own JSON, checked before tinygltf reads it, for what tinygltf cannot take or
// leaves to its caller:
// - nesting deeper than kMaxJsonDepth (thousands of arrays in "extras" overflowed the stack inside
//   the parser), found by a scan of the text before any parser sees it;
// - glTF 1.0 (tinygltf's errors name whatever differs first), and a required extension the engine
//   does not support (named before an accessor it changes is found broken);
// - the types of the optional properties the engine reads: tinygltf skips one of the wrong type
//   ("intensity": "5", "translation": "1 2 3") without a word and the object loads with the default,
//   and reads -1 for an index as none. It also reads an absent light range and "range": 0 alike
//   (both 0), where the second is forbidden.
// JSON that does not parse is left to tinygltf to report.
#pragma once

#include <cstddef>
#include <span>
#include <string>

namespace lpv::engine {

// Far above any real file's nesting (a glTF's own structure is 6 deep; "extras" are the authors').
inline constexpr size_t kMaxJsonDepth = 256;

// Throws SceneError naming `path`, the object and the property, and what was expected.
void checkGltfJson(const std::string& path, bool binary, std::span<const char* const> supportedExtensions);

} // namespace lpv::engine
