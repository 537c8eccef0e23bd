// A closed room 6 x 3 x 4 m inside (x -3..3, y 0..3, z -2..2), walls 0.2 m, on a ground 40 m
// across: a room inside a much larger scene, whose open space is measured in half-metre voxels.
#pragma once

#include "engine/scene/MeshBuilder.h"
#include "engine/scene/Scene.h"

namespace lpv::test {

inline engine::Scene roomOnGround() {
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

} // namespace lpv::test
