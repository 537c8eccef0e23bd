// Thin walls and the lookup, on each backend: the Cornell box seen from inside, once open (its
// ceiling's opening lets the sun onto the floor, its front is open) and once sealed (a lid over the
// opening, a front wall). Sealed, no light reaches the room: what the room's surfaces read is light
// of the sunlit roof and outer walls that came through the 0.1 m walls, thinner than a cell.
#include "../render/CornellFrame.h"
#include "../support/TestDevice.h"

#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"

#include <doctest/doctest.h>

#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::test;

namespace {

// The mean indirect irradiance (all channels) of the view from inside the box, with `settings` on
// top of GI with the indirect view.
double roomIndirect(rhi::Device& device, bool sealed, const std::vector<std::string>& settings) {
    engine::Scene scene = engine::buildCornellBox();
    if (sealed) {
        engine::MeshBuilder b(scene);
        b.begin("lid", 0);
        b.box({-0.65f, 5.5f, -0.65f}, {0.65f, 5.6f, 0.65f});
        b.finish();
        b.begin("front wall", 0);
        b.box({-2.85f, -0.1f, 2.75f}, {2.85f, 5.6f, 2.85f});
        b.finish();
    }
    scene.camera->position = {0.0f, 2.75f, 2.6f};
    scene.camera->verticalFov = 1.4f; // 80 degrees: the back and side walls, the floor, the boxes
    scene.updateBounds();
    std::vector<std::string> all{"gi.enabled=true", "render.debug_view=indirect", "render.ssao=false",
                                 "gi.occlusion=true"};
    all.insert(all.end(), settings.begin(), settings.end());
    const CornellFrame f = renderSceneFrame(device, scene, all, {}, 320, 180, 3);
    double sum = 0.0;
    for (uint32_t y = 0; y < f.hdr.height; ++y)
        for (uint32_t x = 0; x < f.hdr.width; ++x) {
            const glm::vec4 v = f.hdr.at(x, y);
            sum += (v.r + v.g + v.b) / 3.0;
        }
    return sum / double(f.hdr.width * f.hdr.height);
}

} // namespace

TEST_CASE("gi: the lookup does not read the light beyond a wall thinner than a cell (occlusion)") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            for (const bool damping : {true, false}) {
                // One cascade of 0.34 m cells holds the whole room: the finest cascade's lookup.
                const std::vector<std::string> settings{
                    "gi.cascades=1", "gi.cell_size=0.34", "gi.iterations=16",
                    std::string("gi.damping=") + (damping ? "true" : "false")};
                const double open = roomIndirect(*device, false, settings);
                const double sealed = roomIndirect(*device, true, settings);
                MESSAGE(backend.name << ", damping " << damping << ": the room's mean indirect light open "
                                     << open << ", sealed " << sealed);
                // The open room is lit: the sun's patch on the floor lights it.
                CHECK(open > 1e-3);
                // Sealed, what is left is the volume's own leak through the walls' edges and
                // corners. Measured (all three backends alike): 0.39% with damping, 7.4% without;
                // before the light's coverage was closed over one-cell holes (the sun grazes the
                // back wall's outside and covers it patchily) 3.4% and 23%; before the lookup's
                // camera-side rule 9% and 29% (the walls meeting the back wall snap to faces 3 cm
                // into the room, and their points in those 3 cm read the back wall's sunlit
                // outside); with a lookup that filtered across the walls 48% and 87%.
                CHECK(sealed < (damping ? 0.02 : 0.12) * open);
            }
        }
    }
}

TEST_CASE("gi: every cascade's lookup keeps to its open faces with gi.lookup_occlusion (occlusion)") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // The sample game's settings: three cascades, the room reaching into the coarse ones.
            const auto sealedRoom = [&](bool everyCascade) {
                return roomIndirect(
                    *device, true,
                    {"gi.cascades=3", "gi.cell_size=0.17", "gi.iterations=16",
                     "gi.coarse_camera_occlusion=false",
                     std::string("gi.lookup_occlusion=") + (everyCascade ? "true" : "false")});
            };
            const double finestOnly = sealedRoom(false), every = sealedRoom(true);
            MESSAGE(
                backend.name << ": the sealed room's mean indirect light, the finest cascade's lookup kept "
                             << "inside " << finestOnly << ", every cascade's " << every);
            CHECK(finestOnly > 0.0);
            // Measured (all three backends alike): 0.0039 and 0.00034 (0.0071 and 0.0029 before the
            // light's coverage was closed over one-cell holes), both without the coarse cascades'
            // camera areas (the next test).
            CHECK(every < 0.2 * finestOnly);
        }
    }
}

TEST_CASE("gi: the coarse cascades' camera areas keep the sunlit outside out of a sealed room (occlusion)") {
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            // The sample game's settings, every cascade's lookup kept to its faces (the default).
            const auto room = [&](bool sealed, bool coarseCamera) {
                return roomIndirect(
                    *device, sealed,
                    {"gi.cascades=3", "gi.cell_size=0.17", "gi.iterations=16",
                     std::string("gi.coarse_camera_occlusion=") + (coarseCamera ? "true" : "false")});
            };
            const double openWithout = room(false, false), sealedWithout = room(true, false);
            const double openWith = room(false, true), sealedWith = room(true, true);
            MESSAGE(backend.name
                    << ": the room's mean indirect light without the coarse cascades' camera areas open "
                    << openWithout << ", sealed " << sealedWithout << "; with them open " << openWith
                    << ", sealed " << sealedWith);
            // Without them the walls the sun does not see block nothing in the coarse cascades, and
            // the light of the sunlit roof and outer walls comes through.
            CHECK(sealedWithout > 0.0);
            CHECK(sealedWith < 0.5 * sealedWithout);
            // The open room keeps most of its light: what it loses is the same outside light, which
            // reached it through the walls too.
            CHECK(openWith > 0.7 * openWithout);
        }
    }
}
