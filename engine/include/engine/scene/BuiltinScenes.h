// Scenes made in code, chosen by name (--scene cornell, --scene atrium, --scene lights).
#pragma once

#include "engine/scene/Scene.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lpv::engine {

// The Cornell box: 5.5 m, red wall at -x, green at +x, white floor, ceiling and back wall, a short
// and a tall box, open toward +z where the camera stands; the sun enters through a square opening
// in the ceiling and lights the floor and the boxes.
Scene buildCornellBox();

// An open court in the spirit of the Sponza atrium: two stories of arcades with columns and arches
// around a court, a roof opening for the sun, coloured cloth banners and clutter, materials with
// textures made in code. About 250k triangles at detail 1.0; `detail` scales the tessellation.
Scene buildAtrium(float detail = 1.0f);
// A spot light 8 m over the atrium's court, looking down at one side's columns (not part of the
// scene: the RSM level-of-detail tests and lpv_bench's spot light figures add it).
Light atriumCourtSpot();

// A 7 m hall at night ("lights"): a floor and three walls, a dim moon, `pointLights` small coloured
// point lights (range 1.2 m, 0.3 m over the floor on a square grid, no light next to one of its own
// colour) and three spot lights on the back wall. For the LPV's analytic lights.
Scene buildLightHall(uint32_t pointLights = 144);

std::vector<std::string> builtinSceneNames();
// True when `name` is a built-in scene name (not a path).
bool isBuiltinScene(std::string_view name);
Scene buildBuiltinScene(std::string_view name, float detail = 1.0f);

} // namespace lpv::engine
