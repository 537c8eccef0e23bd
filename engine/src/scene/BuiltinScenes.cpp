// Built-in scenes by name.
#include "engine/scene/BuiltinScenes.h"

#include <stdexcept>

namespace lpv::engine {

std::vector<std::string> builtinSceneNames() {
    return {"cornell", "atrium"};
}

bool isBuiltinScene(std::string_view name) {
    return name == "cornell" || name == "atrium";
}

Scene buildBuiltinScene(std::string_view name, float detail) {
    if (name == "cornell") return buildCornellBox();
    if (name == "atrium") return buildAtrium(detail);
    throw std::invalid_argument("unknown built-in scene '" + std::string(name) + "' (cornell, atrium)");
}

} // namespace lpv::engine
