// A level of 50,000 draws (issue 47): every box its own mesh and instance, so its own draw. Each
// draw pushed its transform and material into the frame's uniform ring, and 20,000 of them
// overflowed it ("pushUniforms: more than 4194304 bytes in one frame"); the draws' records now sit
// in a storage buffer sized from the scene (GpuScene::drawRecords(), category scene.draws), and a
// draw passes its index as its first instance.
#include "CornellFrame.h"

#include "../support/TestDevice.h"

#include "engine/render/GpuScene.h"
#include "engine/scene/MeshBuilder.h"

#include <doctest/doctest.h>

#include <glm/geometric.hpp>

#include <string>

using namespace lpv;
using namespace lpv::test;

namespace {

constexpr uint32_t kColumns = 250, kRows = 200, kBoxes = kColumns * kRows; // 50,000
constexpr uint32_t kBandRows = 20;                                         // 5,000 draws a band
constexpr uint32_t kBands = kRows / kBandRows;
constexpr float kSpacing = 0.2f;

// Box i's material: bands of 5,000 consecutive draws alternate red and green, and the last band is
// blue, so a pixel shows the record of a draw from its own band (a draw reading another's record,
// the first one's or one 65,536 away, shows another colour).
uint32_t bandMaterial(uint32_t band) {
    return band == kBands - 1 ? 2u : band % 2;
}

constexpr float kBoxHeight = 0.3f; // one height: a pixel covers about two boxes

glm::vec3 boxCentre(uint32_t row, uint32_t column) {
    return {(float(column) + 0.5f) * kSpacing - 0.5f * kSpacing * kColumns, 0.0f,
            (float(row) + 0.5f) * kSpacing - 0.5f * kSpacing * kRows};
}

// Rows of touching boxes seen from straight above: every pixel shows the top of some box.
engine::Scene boxField() {
    engine::Scene scene;
    scene.name = "box field";
    scene.materials = {{"red", {0.8f, 0.1f, 0.1f, 1.0f}},
                       {"green", {0.1f, 0.8f, 0.1f, 1.0f}},
                       {"blue", {0.1f, 0.1f, 0.8f, 1.0f}}};
    scene.vertices.reserve(size_t(kBoxes) * 24);
    scene.indices.reserve(size_t(kBoxes) * 36);
    scene.meshes.reserve(kBoxes);
    scene.instances.reserve(kBoxes);
    engine::MeshBuilder mb(scene);
    for (uint32_t row = 0; row < kRows; ++row)
        for (uint32_t column = 0; column < kColumns; ++column) {
            const uint32_t i = row * kColumns + column;
            const glm::vec3 c = boxCentre(row, column);
            mb.begin("box " + std::to_string(i), bandMaterial(row / kBandRows));
            mb.box(c - glm::vec3(0.5f * kSpacing, 0.0f, 0.5f * kSpacing),
                   c + glm::vec3(0.5f * kSpacing, kBoxHeight, 0.5f * kSpacing));
            mb.finish();
        }
    engine::Light sun;
    sun.name = "sun";
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    engine::Camera camera;
    camera.position = {0.0f, 45.0f, 0.0f};
    camera.forward = {0.0f, -1.0f, 0.0f};
    camera.up = {0.0f, 0.0f, -1.0f};
    camera.nearPlane = 30.0f;
    camera.farPlane = 60.0f;
    scene.camera = camera;
    scene.updateBounds();
    return scene;
}

// The G-buffer albedo at the middle of each band (its boxes' tops) has the band's colour.
void checkBands(const CornellFrame& f) {
    for (uint32_t band = 0; band < kBands; ++band) {
        const uint32_t row = band * kBandRows + kBandRows / 2, column = kColumns / 2;
        const glm::vec3 top = boxCentre(row, column) + glm::vec3(0.0f, kBoxHeight, 0.0f);
        uint32_t x = 0, y = 0;
        REQUIRE_MESSAGE(f.pixelOf(top, x, y), "band " << band << "'s middle box top is not visible");
        const glm::vec4 a = f.albedo.at(x, y);
        const int material = int(bandMaterial(band));
        INFO("band " << band << " (draws " << band * kBandRows * kColumns << "+) at pixel " << x << "," << y
                     << ": albedo " << a.r << " " << a.g << " " << a.b);
        // Stored sRGB: the material's 0.8 reads about 0.91, its 0.1 about 0.35.
        for (int c = 0; c < 3; ++c)
            CHECK(a[c] == doctest::Approx(c == material ? 0.906f : 0.349f).epsilon(0.02));
    }
}

} // namespace

TEST_CASE("render: a level of 50,000 draws renders, with and without GI, its draw records in scene.draws") {
    const engine::Scene scene = boxField();
    REQUIRE(scene.instances.size() == kBoxes);
    REQUIRE(scene.meshes.size() == kBoxes);
    for (const auto& backend : selectedBackends()) {
        SUBCASE(backend.name.c_str()) {
            TestDevice device(backend);
            for (const bool gi : {false, true}) {
                CAPTURE(gi);
                uint64_t drawBytes = 0;
                const CornellFrame f = renderSceneFrame(
                    *device, scene, {"render.ssao=false", gi ? "gi.enabled=true" : "gi.enabled=false"},
                    [&](engine::Renderer&) { drawBytes = device->allocations().bytesIn("scene.draws"); }, 160,
                    90);
                // One record and one index (the multi-draws' per-instance stream) per draw, made at
                // setScene; none once the scene is gone.
                CHECK(drawBytes == uint64_t(kBoxes) * (sizeof(engine::DrawUniforms) + sizeof(uint32_t)));
                CHECK(device->allocations().bytesIn("scene.draws") == 0);
                checkBands(f);
                // The sun lights the boxes' tops (the ambient term alone gives 0.044).
                CHECK(meanLuminance(f.output) > 0.2);
                if (gi) {
                    // The RSM's draws (the same records) put the sunlit tops' light into the volume.
                    REQUIRE(!f.cascadeVolumes.empty());
                    double red = 0.0; // the red SH volume's constant (x) coefficient
                    for (const glm::vec4& t : f.cascadeVolumes[0][0].texels)
                        red += double(t.x);
                    CHECK(red > 0.0);
                }
            }
            device.expectSilent();
        }
    }
}
