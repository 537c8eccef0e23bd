// What loading a broken glTF file reports, for the scene tests that check the message.
#pragma once

#include "engine/scene/SceneLoading.h"

#include <string>

namespace lpv::test {

// The SceneError's message for loading this file, or "(no error)". Any other exception escapes
// and fails the test.
inline std::string gltfErrorOf(const std::string& path) {
    try {
        engine::loadGltf(path);
    } catch (const engine::SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

} // namespace lpv::test
