// The types of the optional glTF properties the engine reads, checked on the file's own JSON.
// tinygltf skips an optional property of the wrong type ("intensity": "5", "translation": "1 2 3")
// without a word, and the object loads with the default: the scene looks wrong and nothing says
// why. It also reads an absent light range and "range": 0 alike (both 0), where the second is
// forbidden. Runs after tinygltf has read the file, so the JSON is known to parse.
#pragma once

#include <string>

namespace lpv::engine {

// Throws SceneError naming `path`, the object and the property, and what was expected.
void checkGltfJsonTypes(const std::string& path, bool binary);

} // namespace lpv::engine
