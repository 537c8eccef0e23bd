// glTF files that viewers show and the engine once refused: triangle strips and fans (made lists, in
// glTF's winding), points and lines among triangles (skipped, with one warning), and sparse
// accessors (applied over their bufferView, or over zeros without one).
#include "GltfErrorOf.h"
#include "engine/scene/SceneLoading.h"
#include "platforms/Log.h"

#include <doctest/doctest.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

using namespace lpv::engine;
using nlohmann::json;

namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = uint32_t(bytes[i]) << 16 |
                           (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        out += kDigits[n >> 18 & 63];
        out += kDigits[n >> 12 & 63];
        out += i + 1 < bytes.size() ? kDigits[n >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
    }
    return out;
}

template <typename T> void append(std::vector<uint8_t>& bytes, std::initializer_list<T> values) {
    for (T v : values) {
        const size_t at = bytes.size();
        bytes.resize(at + sizeof(T));
        std::memcpy(bytes.data() + at, &v, sizeof(T));
    }
}

// A unit square in z = 0, facing +z. Accessors: 0 its corners 0 1 2 3 (a strip's order), 1 the same as
// 0 1 3 2 (a fan's), 2 and 3 those orders as uint16 indices of accessor 0, 4 accessor 0 with sparse
// values (5, 5, 0) at 1 and (7, 7, 0) at 3, 5 those sparse values over zeros (no bufferView).
json square() {
    std::vector<uint8_t> b;
    append<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
    append<float>(b, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
    append<uint16_t>(b, {0, 1, 2, 3, 0, 1, 3, 2, 1, 3});
    append<float>(b, {5, 5, 0, 7, 7, 0});
    json g = json::parse(R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"name": "square", "primitives": [{"attributes": {"POSITION": 0}, "indices": 2, "mode": 5}]}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 8},
                  {"buffer": 0, "byteOffset": 104, "byteLength": 8},
                  {"buffer": 0, "byteOffset": 112, "byteLength": 4},
                  {"buffer": 0, "byteOffset": 116, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5123, "count": 4, "type": "SCALAR"},
                {"bufferView": 3, "componentType": 5123, "count": 4, "type": "SCALAR"},
                {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "sparse": {"count": 2, "indices": {"bufferView": 4, "componentType": 5123},
                            "values": {"bufferView": 5}}},
                {"componentType": 5126, "count": 4, "type": "VEC3",
                 "sparse": {"count": 2, "indices": {"bufferView": 4, "componentType": 5123},
                            "values": {"bufferView": 5}}}]
})");
    g["buffers"] = {{{"byteLength", b.size()}, {"uri", "data:application/octet-stream;base64," + base64(b)}}};
    return g;
}

std::string write(const std::string& name, const json& gltf) {
    static const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("lpv_gltf_viewer_tests_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << gltf.dump();
    return path;
}

// Every triangle's geometric normal (unnormalized), in index order.
std::vector<glm::vec3> faceNormals(const Scene& s) {
    std::vector<glm::vec3> normals;
    for (size_t i = 0; i + 2 < s.indices.size(); i += 3) {
        const glm::vec3 a = s.vertices[s.indices[i]].position, b = s.vertices[s.indices[i + 1]].position,
                        c = s.vertices[s.indices[i + 2]].position;
        normals.push_back(glm::cross(b - a, c - a));
    }
    return normals;
}

// Loads `gltf` with its one primitive as `primitive`; the square's two triangles must face +z.
void checkSquare(const std::string& name, const json& primitive) {
    json g = square();
    g["meshes"][0]["primitives"] = json::array({primitive});
    const Scene s = loadGltf(write(name, g));
    REQUIRE(s.triangleCount() == 2);
    for (const glm::vec3& n : faceNormals(s))
        CHECK(n.z == doctest::Approx(1.0f));
}

} // namespace

TEST_CASE("glTF viewer files: triangle strips and fans become lists that face the same way") {
    checkSquare("strip.gltf", {{"attributes", {{"POSITION", 0}}}, {"indices", 2}, {"mode", 5}});
    checkSquare("strip-unindexed.gltf", {{"attributes", {{"POSITION", 0}}}, {"mode", 5}});
    checkSquare("fan.gltf", {{"attributes", {{"POSITION", 0}}}, {"indices", 3}, {"mode", 6}});
    checkSquare("fan-unindexed.gltf", {{"attributes", {{"POSITION", 1}}}, {"mode", 6}});
    // The strip's second triangle is (v1, v3, v2), as glTF 2.0 gives it.
    json g = square();
    const Scene s = loadGltf(write("strip-order.gltf", g));
    CHECK(s.indices == std::vector<uint32_t>{0, 1, 2, 1, 3, 2});
}

TEST_CASE("glTF viewer files: points and lines are skipped with one warning; alone, nothing to draw") {
    std::vector<std::string> warnings;
    auto previous = lpv::log::setSink([&](lpv::log::Level level, std::string_view m) {
        if (level == lpv::log::Level::Warning) warnings.emplace_back(m);
    });
    json g = square();
    for (const int mode : {0, 1, 2, 3})
        g["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", mode}});
    const std::string path = write("lines.gltf", g);
    const Scene s = loadGltf(path);
    lpv::log::setSink(previous);
    CHECK(s.triangleCount() == 2);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] == path + ": 4 primitives of points or lines skipped; only triangles are drawn");

    json lines = square();
    lines["meshes"][0]["primitives"][0]["mode"] = 1;
    const std::string linesPath = write("onlylines.gltf", lines);
    CHECK(lpv::test::gltfErrorOf(linesPath) ==
          linesPath +
              ": has no meshes to draw (1 primitive of points or lines skipped: only triangles are drawn)");
    json seven = square();
    seven["meshes"][0]["primitives"][0]["mode"] = 7;
    const std::string sevenPath = write("mode7.gltf", seven);
    CHECK(lpv::test::gltfErrorOf(sevenPath) ==
          sevenPath + ": mesh 0 'square' primitive 0: primitive mode 7 is not a glTF mode (0 to 6)");
    json two = square();
    two["accessors"][2]["count"] = 2;
    const std::string twoPath = write("strip2.gltf", two);
    CHECK(
        lpv::test::gltfErrorOf(twoPath) ==
        twoPath +
            ": mesh 0 'square' primitive 0: TRIANGLE_STRIP has 2 vertices, fewer than the 3 of one triangle");
}

TEST_CASE("glTF viewer files: sparse accessors are applied, over the bufferView or over zeros") {
    for (const int accessor : {4, 5}) {
        json g = square();
        g["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = accessor;
        const Scene s = loadGltf(write("sparse" + std::to_string(accessor) + ".gltf", g));
        REQUIRE(s.vertices.size() == 4);
        CHECK(s.vertices[0].position == glm::vec3(0, 0, 0));
        CHECK(s.vertices[1].position == glm::vec3(5, 5, 0));
        CHECK(s.vertices[2].position == (accessor == 4 ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 0)));
        CHECK(s.vertices[3].position == glm::vec3(7, 7, 0));
    }
    // A sparse index out of range or out of order, and values past their bufferView, are named.
    const auto errorWith = [](const std::string& name, const std::function<void(json&)>& change) {
        json g = square();
        g["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 4;
        change(g);
        const std::string path = write(name, g);
        return lpv::test::gltfErrorOf(path).substr(path.size() + 2);
    };
    // Indices 3, 2 (the fan's last two): the second is not above the first.
    CHECK(errorWith("sparseorder.gltf", [](json& g) {
              g["accessors"][4]["sparse"]["indices"] = {
                  {"bufferView", 3}, {"byteOffset", 4}, {"componentType", 5123}};
          }) == "accessor 4: sparse index 2 (number 1) is not greater than the one before it");
    CHECK(errorWith("sparserange.gltf", [](json& g) { g["accessors"][4]["count"] = 3; }) ==
          "accessor 4: sparse index 3 (number 1) is out of range (3 elements)");
    CHECK(errorWith("sparsevalues.gltf",
                    [](json& g) { g["accessors"][4]["sparse"]["values"]["byteOffset"] = 4; }) ==
          "accessor 4: sparse.values: 2 elements of 12 bytes from byte 4 do not fit in bufferView 5 (24 "
          "bytes)");
    CHECK(errorWith("sparsecount.gltf", [](json& g) { g["accessors"][4]["sparse"]["count"] = 5; }) ==
          "accessor 4: sparse.count 5 must be in [1, 4] (the accessor's count)");
}
