// The open space around a point (engine/scene/OpenSpace.h), which gi.cell_size = auto sizes the
// finest cascade to: a closed room, a room seen from outside, the open ground.
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"
#include "engine/scene/OpenSpace.h"

#include <doctest/doctest.h>

using namespace lpv;

namespace {

// A closed room 6 x 3 x 4 m inside, walls 0.2 m, on a ground 40 m across.
engine::Scene roomOnGround() {
    engine::Scene scene;
    scene.materials = {{"white", {0.7f, 0.7f, 0.7f, 1.0f}}};
    engine::MeshBuilder b(scene);
    b.begin("ground", 0);
    b.box({-20.0f, -0.2f, -20.0f}, {20.0f, 0.0f, 20.0f});
    b.finish();
    b.begin("room", 0);
    b.box({-3.2f, 3.0f, -2.2f}, {3.2f, 3.2f, 2.2f}); // ceiling
    b.box({-3.2f, 0.0f, -2.2f}, {-3.0f, 3.0f, 2.2f});
    b.box({3.0f, 0.0f, -2.2f}, {3.2f, 3.0f, 2.2f});
    b.box({-3.0f, 0.0f, -2.2f}, {3.0f, 3.0f, -2.0f});
    b.box({-3.0f, 0.0f, 2.0f}, {3.0f, 3.0f, 2.2f});
    b.finish();
    scene.updateBounds();
    return scene;
}

} // namespace

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
