// The open space around a point (engine/scene/OpenSpace.h), which gi.cell_size = auto sizes the
// finest cascade to: a closed room, a room seen from outside, the open ground.
#include "../support/RoomOnGround.h"

#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/OpenSpace.h"

#include <doctest/doctest.h>

using namespace lpv;
using lpv::test::roomOnGround;

TEST_CASE("engine: the open space around a point is its room's, or the scene's in the open") {
    const engine::Scene scene = roomOnGround();
    const engine::OpenSpace space(scene);
    const float voxel = 40.0f / 64.0f;
    // Inside, the room's longest side (6 m), to within a voxel on each side.
    CHECK(space.extentAround({1.0f, 1.5f, 0.5f}) == doctest::Approx(6.0f).epsilon(2.0f * voxel / 6.0f));
    // Against a wall, still the room: the voxel the point lies in does not count.
    CHECK(space.extentAround({2.9f, 1.5f, 0.0f}) == doctest::Approx(6.0f).epsilon(2.0f * voxel / 6.0f));
    // Outdoors, above the ground beside the room: the scene's 40 m.
    CHECK(space.extentAround({10.0f, 1.5f, 10.0f}) >= 38.0f);
    // Outside the scene's bounds: its largest side.
    CHECK(space.extentAround({0.0f, 50.0f, 0.0f}) == doctest::Approx(40.0f));
    // The built-in Cornell box from its camera, outside the box: the box, 5.7 m across.
    const engine::Scene cornell = engine::buildCornellBox();
    CHECK(engine::OpenSpace(cornell).extentAround(cornell.camera->position) ==
          doctest::Approx(5.7f).epsilon(0.01));
    CHECK(engine::OpenSpace(engine::Scene{}).extentAround({0.0f, 0.0f, 0.0f}) == 0.0f);
}

TEST_CASE("engine: the room around a point holds its surfaces, to within a voxel beyond them") {
    const engine::Scene scene = roomOnGround();
    const engine::OpenSpace space(scene);
    const float voxel = 40.0f / 64.0f;
    // The free span stops at the first occupied voxel's near side, short of the walls by up to a
    // voxel; the room reaches that voxel's far side, past the walls' inner faces.
    const engine::Bounds room = space.roomAround({1.0f, 1.5f, 0.5f});
    const glm::vec3 inner[2] = {{-3.0f, 0.0f, -2.0f}, {3.0f, 3.0f, 2.0f}};
    for (int a = 0; a < 3; ++a) {
        CHECK(room.min[a] <= inner[0][a]);
        CHECK(room.min[a] >= inner[0][a] - voxel);
        CHECK(room.max[a] >= inner[1][a]);
        CHECK(room.max[a] <= inner[1][a] + voxel);
    }
    // Outside the scene's bounds: the bounds; an empty scene: an empty box.
    CHECK(space.roomAround({0.0f, 50.0f, 0.0f}).size().x == doctest::Approx(40.0f));
    CHECK(engine::OpenSpace(engine::Scene{}).roomAround({0.0f, 0.0f, 0.0f}).empty());
}
