// Built-in scenes by name.
#include "engine/scene/BuiltinScenes.h"

#include <stdexcept>

namespace lpv::engine {

std::vector<std::string> builtinSceneNames() {
    return {"cornell", "atrium", "lights"};
}

bool isBuiltinScene(std::string_view name) {
    return name == "cornell" || name == "atrium" || name == "lights";
}

Scene buildBuiltinScene(std::string_view name, float detail) {
    if (name == "cornell") return buildCornellBox();
    if (name == "atrium") return buildAtrium(detail);
    if (name == "lights") return buildLightHall();
    throw std::invalid_argument("unknown built-in scene '" + std::string(name) +
                                "' (cornell, atrium, lights)");
}

} // namespace lpv::engine
