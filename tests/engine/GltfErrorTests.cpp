// Broken glTF files, each the valid one-triangle file below with one change. Every one must be a
// SceneError whose message names the file and the problem: not a crash, not a library's raw message
// without the file, and not a silent default.
#include "engine/scene/SceneLoading.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

using namespace lpv::engine;
using nlohmann::json;

namespace {

// One triangle: 3 float positions (36 bytes), then 3 uint16 indices (6 bytes and 2 of padding).
json triangle() {
    return json::parse(R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=",
               "byteLength": 44}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}]
})");
}

// A folder of this process's own, so that test runs side by side (other build trees) share no files.
struct TestDir {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("lpv_gltf_error_tests_" + std::to_string(::getpid()));
    TestDir() { std::filesystem::create_directories(path); }
    ~TestDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};

const std::filesystem::path& testDir() {
    static const TestDir dir;
    return dir.path;
}

std::string pathOf(const std::string& name) {
    return (testDir() / name).string();
}

// The SceneError's message for loading this file, or "(no error)". Any other exception escapes
// and fails the test.
std::string errorOf(const std::string& path) {
    try {
        loadGltf(path);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string errorOf(const std::string& name, const json& gltf) {
    const std::string path = pathOf(name);
    std::ofstream(path, std::ios::binary) << gltf.dump();
    return errorOf(path);
}

} // namespace

TEST_CASE("glTF errors: the unchanged triangle loads") {
    CHECK(errorOf("ok.gltf", triangle()) == "(no error)");
    CHECK(loadGltf(pathOf("ok.gltf")).triangleCount() == 1);
}

TEST_CASE("glTF errors: a directory given as the scene") {
    const std::string path = pathOf("d.gltf");
    std::filesystem::create_directories(path);
    CHECK(errorOf(path) == path + ": is a directory, not a glTF file");
}

TEST_CASE("glTF errors: a file that cannot be opened gives the system's reason") {
    const std::string path = pathOf("missing.gltf");
    CHECK(errorOf(path) == path + ": cannot open the file: No such file or directory");
}
