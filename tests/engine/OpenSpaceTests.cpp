// The open space around a point (engine/scene/OpenSpace.h), which gi.cell_size = auto sizes the
// finest cascade to: a closed room, a room seen from outside, the open ground.
#include "../support/RoomOnGround.h"

#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/OpenSpace.h"

#include <doctest/doctest.h>

using namespace lpv;
using lpv::test::roomOnGround;

TEST_CASE("engine: the room around a point is its room, or the scene in the open") {
    const engine::Scene scene = roomOnGround();
    const engine::OpenSpace space(scene);
    const float voxel = 40.0f / 64.0f;
    // Inside, the room's longest side (6 m), and at most a voxel more beyond each wall.
    const float inside = space.roomAround({1.0f, 1.5f, 0.5f}).largestSide();
    CHECK(inside >= 6.0f);
    CHECK(inside <= 6.0f + 2.0f * voxel);
    // Against a wall, still the room: the voxel the point lies in does not count (where it holds
    // the wall, the room reaches one voxel further on that side, 6.875 m here).
    const float againstWall = space.roomAround({2.9f, 1.5f, 0.0f}).largestSide();
    CHECK(againstWall >= 6.0f);
    CHECK(againstWall <= 6.0f + 2.0f * voxel);
    // Outdoors, above the ground beside the room: the scene's 40 m.
    CHECK(space.roomAround({10.0f, 1.5f, 10.0f}).largestSide() >= 38.0f);
    // Outside the scene's bounds: its largest side.
    CHECK(space.roomAround({0.0f, 50.0f, 0.0f}).largestSide() == doctest::Approx(40.0f));
    // The built-in Cornell box from its camera, outside the box: the box, 5.7 m across.
    const engine::Scene cornell = engine::buildCornellBox();
    CHECK(engine::OpenSpace(cornell).roomAround(cornell.camera->position).largestSide() ==
          doctest::Approx(5.7f).epsilon(0.01));
    CHECK(engine::OpenSpace(engine::Scene{}).roomAround({0.0f, 0.0f, 0.0f}).largestSide() == 0.0f);
}

TEST_CASE("engine: the room around a point holds its surfaces, to within a voxel beyond them") {
    const engine::Scene scene = roomOnGround();
    const engine::OpenSpace space(scene);
    const float voxel = 40.0f / 64.0f;
    // The room reaches the far side of the first occupied voxel, past the walls' inner faces (the
    // free span alone, to that voxel's near side, fell short of them by up to a voxel).
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
