// Broken glTF files, each the valid one-triangle file below with one change. Every one must be a
// SceneError whose message names the file and the problem: not a crash, not a library's raw message
// without the file, and not a silent default.
#include "engine/scene/SceneLoading.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

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

namespace {

// A broken variant of the triangle: the file to write, the change, and the problem the error must name.
struct BrokenFile {
    const char* file;
    std::function<void(json&)> change;
    std::string problem;
};

void checkErrors(const std::vector<BrokenFile>& cases) {
    for (const BrokenFile& c : cases) {
        json gltf = triangle();
        c.change(gltf);
        CHECK(errorOf(c.file, gltf) == pathOf(c.file) + ": " + c.problem);
    }
}

} // namespace

TEST_CASE("glTF errors: an index to an element that does not exist names the element") {
    checkErrors({
        {"position5.gltf", [](json& g) { g["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 5; },
         "mesh 0 'tri' primitive 0: attribute POSITION refers to accessor 5, which does not exist"},
        {"normal7.gltf", [](json& g) { g["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 7; },
         "mesh 0 'tri' primitive 0: attribute NORMAL refers to accessor 7, which does not exist"},
        {"indices-2.gltf", [](json& g) { g["meshes"][0]["primitives"][0]["indices"] = -2; },
         "mesh 0 'tri' primitive 0: \"indices\" refers to accessor -2, which does not exist"},
        {"material2.gltf", [](json& g) { g["meshes"][0]["primitives"][0]["material"] = 2; },
         "mesh 0 'tri' primitive 0 refers to material 2, which does not exist"},
        {"view4.gltf", [](json& g) { g["accessors"][0]["bufferView"] = 4; },
         "accessor 0 refers to bufferView 4, which does not exist"},
        {"buffer3.gltf", [](json& g) { g["bufferViews"][0]["buffer"] = 3; },
         "bufferView 0 refers to buffer 3, which does not exist"},
        {"basecolor3.gltf",
         [](json& g) {
             g["materials"] = json::parse(
                 R"([{"name": "paint", "pbrMetallicRoughness": {"baseColorTexture": {"index": 3}}}])");
         },
         "material 0 'paint': baseColorTexture refers to texture 3, which does not exist"},
        {"image4.gltf", [](json& g) { g["textures"] = json::parse(R"([{"source": 4}])"); },
         "texture 0 refers to image 4, which does not exist"},
        {"sampler2.gltf", [](json& g) { g["textures"] = json::parse(R"([{"sampler": 2}])"); },
         "texture 0 refers to sampler 2, which does not exist"},
        {"mesh3.gltf", [](json& g) { g["nodes"][0]["mesh"] = 3; },
         "node 0 refers to mesh 3, which does not exist"},
        {"camera1.gltf", [](json& g) { g["nodes"][0]["camera"] = 1; },
         "node 0 refers to camera 1, which does not exist"},
        {"child5.gltf", [](json& g) { g["nodes"][0]["children"] = {5}; },
         "node 0: child refers to node 5, which does not exist"},
        {"light2.gltf",
         [](json& g) {
             g["nodes"][0]["extensions"] = json::parse(R"({"KHR_lights_punctual": {"light": 2}})");
         },
         "node 0 refers to light 2, which does not exist"},
        {"root4.gltf",
         [](json& g) {
             g["scenes"][0]["nodes"] = {0, 4};
         },
         "scene 0 refers to node 4, which does not exist"},
        {"scene3.gltf", [](json& g) { g["scene"] = 3; }, "\"scene\" refers to scene 3, which does not exist"},
    });
}

TEST_CASE("glTF errors: byte ranges past the end are caught however large the numbers") {
    checkErrors({
        {"count.gltf", [](json& g) { g["accessors"][0]["count"] = 4611686018427387904ull; },
         "accessor 0: 4611686018427387904 elements of 12 bytes, 12 bytes apart from byte 0, do not fit in "
         "bufferView 0 (36 bytes)"},
        {"offset.gltf", [](json& g) { g["accessors"][0]["byteOffset"] = 18446744073709551612ull; },
         "accessor 0: 3 elements of 12 bytes, 12 bytes apart from byte 18446744073709551612, do not fit in "
         "bufferView 0 (36 bytes)"},
        {"stride.gltf", [](json& g) { g["bufferViews"][0]["byteStride"] = 252; },
         "accessor 0: 3 elements of 12 bytes, 252 bytes apart from byte 0, do not fit in bufferView 0 (36 "
         "bytes)"},
        {"viewoffset.gltf", [](json& g) { g["bufferViews"][1]["byteOffset"] = 18446744073709551600ull; },
         "bufferView 1 (6 bytes from byte 18446744073709551600) runs past the end of buffer 0 (44 bytes)"},
        {"viewlength.gltf", [](json& g) { g["bufferViews"][1]["byteLength"] = 9; },
         "bufferView 1 (9 bytes from byte 36) runs past the end of buffer 0 (44 bytes)"},
        // tinygltf decodes images during parsing: the range is checked before it reads a byte.
        {"imageview.gltf",
         [](json& g) {
             g["bufferViews"].push_back(
                 json::parse(R"({"buffer": 0, "byteOffset": 40, "byteLength": 100000})"));
             g["images"] = json::parse(R"([{"bufferView": 2, "mimeType": "image/png"}])");
         },
         "not a valid glTF 2.0 file: image 0: bufferView 2 (100000 bytes from byte 40) runs past the end of "
         "buffer 0 (44 bytes)"},
    });
}

TEST_CASE("glTF errors: nodes must form disjoint trees") {
    checkErrors({
        {"selfchild.gltf", [](json& g) { g["nodes"][0]["children"] = {0}; }, "node 0 is its own ancestor"},
        {"loop.gltf",
         [](json& g) { g["nodes"] = json::parse(R"([{"mesh": 0, "children": [1]}, {"children": [0]}])"); },
         "node 0 is its own ancestor"},
        {"twoparents.gltf",
         [](json& g) {
             g["nodes"] = json::parse(R"([{"mesh": 0}, {"children": [0]}, {"name": "b", "children": [0]}])");
             g["scenes"][0]["nodes"] = {1, 2};
         },
         "node 0 has two parents, nodes 1 and 2"},
        {"twice.gltf",
         [](json& g) {
             g["nodes"] = json::parse(R"([{"mesh": 0}, {"name": "a", "children": [0, 0]}])");
             g["scenes"][0]["nodes"] = {1};
         },
         "node 1 'a' lists node 0 twice among its children"},
        {"childroot.gltf",
         [](json& g) {
             g["nodes"] = json::parse(R"([{"mesh": 0}, {"children": [0]}])");
             g["scenes"][0]["nodes"] = {1, 0};
         },
         "scene 0 lists node 0 as a root, but it is a child of node 1"},
        {"rootstwice.gltf",
         [](json& g) {
             g["scenes"][0]["nodes"] = {0, 0};
         },
         "scene 0 lists node 0 twice"},
    });
}

TEST_CASE("glTF errors: a legal hierarchy deeper than the call stack loads") {
    json gltf = triangle();
    constexpr int kDepth = 100000;
    gltf["nodes"] = json::array();
    for (int i = 0; i + 1 < kDepth; ++i)
        gltf["nodes"].push_back({{"children", {i + 1}}});
    gltf["nodes"].push_back({{"mesh", 0}});
    const std::string path = pathOf("deep.gltf");
    std::ofstream(path, std::ios::binary) << gltf.dump();
    CHECK(loadGltf(path).instances.size() == 1);
}

TEST_CASE("glTF errors: without scenes, each tree is drawn once from its root") {
    json gltf = triangle();
    gltf.erase("scene");
    gltf.erase("scenes");
    gltf["nodes"] = json::parse(R"([{"children": [1]}, {"mesh": 0}])");
    const std::string path = pathOf("noscenes.gltf");
    std::ofstream(path, std::ios::binary) << gltf.dump();
    CHECK(loadGltf(path).instances.size() == 1);
}
