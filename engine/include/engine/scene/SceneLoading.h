// Scenes from glTF 2.0 files (.gltf and .glb, through tinygltf) or built-in names. A broken file
// is a SceneError naming the file and the problem; a missing texture only warns and the material
// falls back to its flat base color.
#pragma once

#include "engine/scene/Scene.h"

#include <stdexcept>
#include <string>
#include <string_view>

namespace lpv::engine {

class SceneError : public std::runtime_error {
public:
    SceneError(const std::string& path, const std::string& problem)
        : std::runtime_error(path + ": " + problem) {}
};

// Meshes (indexed, triangles), node transforms, materials (base color factor and texture, normal
// texture, metallic-roughness, emissive), the first camera, and KHR_lights_punctual lights.
Scene loadGltf(const std::string& path);

// A built-in scene name (cornell, atrium, lights) or a path to a glTF file.
Scene loadScene(std::string_view nameOrPath, float detail = 1.0f);

} // namespace lpv::engine
