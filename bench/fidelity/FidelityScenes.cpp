// The fidelity scenes (FidelityScenes.h). The glTF ones come from scripts/make-fidelity-scenes.py.
#include "FidelityScenes.h"

namespace lpv::bench {

std::vector<FidelityScene> fidelityScenes(const std::string& sceneDir) {
    return {
        // The built-in box: the sun through a square opening in the ceiling onto the floor.
        {"cornell", "cornell", {"gi.cell_size=0.2"}, 256, 256, true, 4},
        // The standard Cornell box, open at the front, the sun entering through it onto the floor.
        {"cornell-sun", sceneDir + "/cornell-sun.gltf", {"gi.cell_size=0.2"}, 256, 256, true},
        // The same box lit by a point light under its ceiling; at the default gi.point_light_rsms
        // (1) the light gets a cube RSM of its own, so the volume carries its bounce only (it is lit
        // per pixel, as the reference's direct light is left out of its indirect pass).
        {"cornell-point", sceneDir + "/cornell-point.gltf", {"gi.cell_size=0.2"}, 256, 256, true},
        // A closed room lit through a door from the sunlit ground outside: light leaking through
        // walls shows here.
        {"doorway", sceneDir + "/doorway.gltf", {"gi.cell_size=0.2"}, 256, 256, false},
        // Figures only, at a small size. Cells: 28 span the Cornell boxes, 30 the doorway's room.
        {"atrium", "atrium", {"gi.cell_size=1.0"}, 256, 144, false},
        // The hall's point lights lit per pixel: with gi.analytic_lights the volume carries their direct
        // light too, which the reference's indirect pass leaves out. Their bounce is then missing.
        {"lights", "lights", {"gi.cell_size=0.25", "gi.analytic_lights=false"}, 256, 144, false},
    };
}

FidelityFog fidelityFog() {
    // The standard box with the sun through its front, homogeneous fog of 0.05/m (about half the
    // light crossing the 13.7 m from the camera to the back wall is scattered or absorbed), the
    // engine's default albedo and Henyey-Greenstein g.
    FidelityFog f{"cornell-sun", {}, 128, 128};
    f.medium.density = 0.05f;
    f.medium.albedo = glm::vec3(0.9f);
    f.medium.anisotropy = 0.2f;
    f.medium.missAtSceneBounds = true;
    return f;
}

std::vector<std::string> fidelitySceneNames() {
    std::vector<std::string> names;
    for (const FidelityScene& s : fidelityScenes(""))
        names.push_back(s.name);
    return names;
}

} // namespace lpv::bench
