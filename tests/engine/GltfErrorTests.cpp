// Broken glTF files, each the valid one-triangle file below with one change. Every one must be a
// SceneError whose message names the file and the problem: not a crash, not a library's raw message
// without the file, and not a silent default.
#include "GltfErrorOf.h"
#include "engine/scene/SceneLoading.h"
#include "platforms/Log.h"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

using namespace lpv::engine;
using nlohmann::json;

namespace {

using lpv::test::gltfErrorOf;

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

std::string gltfErrorOf(const std::string& name, const json& gltf) {
    const std::string path = pathOf(name);
    std::ofstream(path, std::ios::binary) << gltf.dump();
    return gltfErrorOf(path);
}

} // namespace

TEST_CASE("glTF errors: the unchanged triangle loads") {
    CHECK(gltfErrorOf("ok.gltf", triangle()) == "(no error)");
    CHECK(loadGltf(pathOf("ok.gltf")).triangleCount() == 1);
}

TEST_CASE("glTF errors: a directory given as the scene") {
    const std::string path = pathOf("d.gltf");
    std::filesystem::create_directories(path);
    CHECK(gltfErrorOf(path) == path + ": is a directory, not a glTF file");
}

TEST_CASE("glTF errors: a file that cannot be opened gives the system's reason") {
    const std::string path = pathOf("missing.gltf");
    CHECK(gltfErrorOf(path) == path + ": cannot open the file: No such file or directory");
}

// It went to the JSON parser, whose error ("last read: 'g'") said nothing of the magic.
TEST_CASE("glTF errors: a .glb that does not begin with the magic says so") {
    const std::string path = pathOf("badmagic.GLB");
    std::ofstream(path, std::ios::binary) << "glTX" << std::string(16, '\0');
    CHECK(gltfErrorOf(path) ==
          path + ": is not a binary glTF (GLB) file: it begins with 'glTX', not the magic 'glTF'");
    const std::string empty = pathOf("empty.glb");
    std::ofstream(empty, std::ios::binary).flush();
    CHECK(gltfErrorOf(empty) == empty + ": is empty, not a binary glTF (GLB) file");
    // A glTF's JSON under a .glb name loads, as it did before the magic was checked.
    const std::string jsonGlb = pathOf("json.glb");
    std::ofstream(jsonGlb, std::ios::binary) << triangle().dump();
    CHECK(gltfErrorOf(jsonGlb) == "(no error)");
    // Also after a byte order mark and more white space than the magic's 4 bytes.
    const std::string bomGlb = pathOf("bom.glb");
    std::ofstream(bomGlb, std::ios::binary) << "\xEF\xBB\xBF\n\n    " << triangle().dump();
    CHECK(gltfErrorOf(bomGlb) == "(no error)");
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
        CHECK(gltfErrorOf(c.file, gltf) == pathOf(c.file) + ": " + c.problem);
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
         "mesh 0 'tri' primitive 0: indices is -2, expected an index (an integer, 0 or more)"},
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

// Core glTF 2.0: positions, normals and tangents are floats (integers need KHR_mesh_quantization,
// which the reader does not support and so refuses when required); texture coordinates may be
// normalized unsigned bytes or shorts. An unsigned-byte position used to load as a fraction of 255.
TEST_CASE("glTF errors: attribute component types the spec forbids") {
    checkErrors({
        {"u8position.gltf", [](json& g) { g["accessors"][0]["componentType"] = 5121; },
         "POSITION accessor 0 has component type 5121, expected float (5126)"},
        {"u16position.gltf",
         [](json& g) {
             g["accessors"][0]["componentType"] = 5123;
             g["accessors"][0]["normalized"] = true;
         },
         "POSITION accessor 0 has component type 5123 (normalized), expected float (5126)"},
        {"u16uv.gltf",
         [](json& g) {
             g["accessors"].push_back(
                 json::parse(R"({"bufferView": 0, "componentType": 5123, "count": 3, "type": "VEC2"})"));
             g["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
         },
         "TEXCOORD_0 accessor 2 has component type 5123, expected float (5126), or normalized unsigned byte "
         "(5121) or short (5123)"},
    });
    json uv = triangle();
    uv["accessors"].push_back(json::parse(
        R"({"bufferView": 0, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"})"));
    uv["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2;
    CHECK(gltfErrorOf("u16uv-normalized.gltf", uv) == "(no error)");
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

namespace {

// Adds `camera` and a node for it, after the triangle's node.
void addCamera(json& g, const std::string& camera, const std::string& node = R"({"camera": 0})") {
    g["cameras"] = json::array({json::parse(camera)});
    g["nodes"].push_back(json::parse(node));
    g["scenes"][0]["nodes"].push_back(g["nodes"].size() - 1);
}

// Adds a KHR_lights_punctual `light` and a node "lamp" for it, after the triangle's node.
void addLight(json& g, const std::string& light, const std::string& transform = "") {
    g["extensionsUsed"] = {"KHR_lights_punctual"};
    g["extensions"]["KHR_lights_punctual"]["lights"] = json::array({json::parse(light)});
    g["nodes"].push_back(json::parse(
        R"({"name": "lamp", "extensions": {"KHR_lights_punctual": {"light": 0}})" + transform + "}"));
    g["scenes"][0]["nodes"].push_back(g["nodes"].size() - 1);
}

} // namespace

TEST_CASE("glTF errors: a version other than 2.x") {
    checkErrors({
        {"v1.gltf", [](json& g) { g["asset"]["version"] = "1.0"; },
         "glTF 1.0 is not supported (asset.version 1.0); convert it to glTF 2.0"},
        {"vword.gltf", [](json& g) { g["asset"]["version"] = "two"; },
         "asset version 'two' is not supported (glTF 2.x only)"},
        {"minversion.gltf", [](json& g) { g["asset"]["minVersion"] = "2.1"; },
         "asset minVersion '2.1' is not supported (glTF 2.0 only)"},
    });
    json later = triangle();
    later["asset"]["version"] = "2.1"; // a later 2.x that asks for nothing past 2.0 loads
    CHECK(gltfErrorOf("v21.gltf", later) == "(no error)");
}

TEST_CASE("glTF errors: camera values the spec forbids") {
    checkErrors({
        {"yfov0.gltf",
         [](json& g) {
             addCamera(g, R"({"type": "perspective", "perspective": {"yfov": 0, "znear": 0.1}})");
         },
         "camera 0: yfov 0 must be in (0, pi)"},
        {"yfovpi.gltf",
         [](json& g) {
             addCamera(g, R"({"type": "perspective", "perspective": {"yfov": 3.5, "znear": 0.1}})");
         },
         "camera 0: yfov 3.5 must be in (0, pi)"},
        {"znear0.gltf",
         [](json& g) { addCamera(g, R"({"type": "perspective", "perspective": {"yfov": 1, "znear": 0}})"); },
         "camera 0: znear 0 must be greater than 0"},
        {"zfar.gltf",
         [](json& g) {
             addCamera(g,
                       R"({"type": "perspective", "perspective": {"yfov": 1, "znear": 0.1, "zfar": 0.05}})");
         },
         "camera 0: zfar 0.05 must be greater than znear 0.1"},
        {"ortho.gltf",
         [](json& g) {
             addCamera(
                 g,
                 R"({"type": "orthographic", "orthographic": {"xmag": 0, "ymag": 1, "znear": 0, "zfar": 9}})");
         },
         "camera 0: xmag and ymag must not be 0"},
        {"camscale.gltf",
         [](json& g) {
             addCamera(g, R"({"type": "perspective", "perspective": {"yfov": 1, "znear": 0.1}})",
                       R"({"name": "eye", "camera": 0, "scale": [1, 0, 1]})");
         },
         "node 1 'eye': its world transform is singular (a zero scale), so camera 0 on it has no direction"},
    });
}

TEST_CASE("glTF errors: light values the spec forbids") {
    checkErrors({
        {"coneequal.gltf",
         [](json& g) {
             addLight(g, R"({"type": "spot", "spot": {"innerConeAngle": 0.5, "outerConeAngle": 0.5}})");
         },
         "light 0: innerConeAngle 0.5 must be in [0, outerConeAngle 0.5)"},
        {"range0.gltf", [](json& g) { addLight(g, R"({"type": "point", "range": 0})"); },
         "light 0: range 0 must be greater than 0"},
        {"hugeintensity.gltf", [](json& g) { addLight(g, R"({"type": "point", "intensity": 1e39})"); },
         "light 0: intensity 1e+39 is too large (at most 3.40282e+38)"},
        {"intensity.gltf", [](json& g) { addLight(g, R"({"type": "point", "intensity": -5})"); },
         "light 0: intensity -5 must be 0 or more"},
        {"innerouter.gltf",
         [](json& g) {
             addLight(g, R"({"type": "spot", "spot": {"innerConeAngle": 1, "outerConeAngle": 0.5}})");
         },
         "light 0: innerConeAngle 1 must be in [0, outerConeAngle 0.5)"},
        {"innerneg.gltf",
         [](json& g) { addLight(g, R"({"type": "spot", "spot": {"innerConeAngle": -0.1}})"); },
         "light 0: innerConeAngle -0.1 must be in [0, outerConeAngle 0.785398)"},
        {"outer.gltf", [](json& g) { addLight(g, R"({"type": "spot", "spot": {"outerConeAngle": 2}})"); },
         "light 0: outerConeAngle 2 must be in (0, pi/2]"},
        {"color.gltf", [](json& g) { addLight(g, R"({"type": "point", "color": [1, 2, 1]})"); },
         "light 0: color (1, 2, 1) must be in [0, 1]"},
        {"lighttype.gltf", [](json& g) { addLight(g, R"({"type": "area"})"); },
         "light 0: type 'area' is not directional, point or spot"},
        {"spotscale.gltf",
         [](json& g) { addLight(g, R"({"type": "spot", "spot": {}})", R"(, "scale": [0, 0, 0])"); },
         "node 1 'lamp': its world transform is singular (a zero scale), so light 0 on it has no direction"},
        {"parentscale.gltf",
         [](json& g) {
             addLight(g, R"({"type": "directional"})");
             g["nodes"].push_back(json::parse(R"({"scale": [2, 0, 2], "children": [1]})"));
             g["scenes"][0]["nodes"] = {0, 2};
         },
         "node 1 'lamp': its world transform is singular (a zero scale), so light 0 on it has no direction"},
    });
}

TEST_CASE("glTF errors: node transforms and material factors the spec forbids") {
    checkErrors({
        {"rotation.gltf",
         [](json& g) {
             g["nodes"][0]["rotation"] = {0, 0, 0, 0};
         },
         "node 0: rotation (0, 0, 0, 0) is not a unit quaternion"},
        {"scale2.gltf",
         [](json& g) {
             g["nodes"][0]["scale"] = {1, 1};
         },
         "node 0: scale has 2 numbers, expected 3"},
        {"metallic.gltf",
         [](json& g) {
             g["materials"] = json::parse(R"([{"pbrMetallicRoughness": {"metallicFactor": 2}}])");
             g["meshes"][0]["primitives"][0]["material"] = 0;
         },
         "material 0: metallicFactor 2 must be in [0, 1]"},
        {"strength.gltf",
         [](json& g) {
             g["materials"] = json::parse(
                 R"([{"name": "glow", "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": -1}}}])");
         },
         "material 0 'glow': KHR_materials_emissive_strength emissiveStrength must be a number, 0 or more"},
    });
}

TEST_CASE("glTF errors: an orthographic camera warns that it is drawn in perspective") {
    std::vector<std::string> warnings;
    auto previous = lpv::log::setSink([&](lpv::log::Level level, std::string_view m) {
        if (level == lpv::log::Level::Warning) warnings.emplace_back(m);
    });
    json gltf = triangle();
    addCamera(gltf,
              R"({"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0, "zfar": 9}})");
    const std::string e = gltfErrorOf("orthowarn.gltf", gltf);
    lpv::log::setSink(previous);
    CHECK(e == "(no error)");
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0] ==
          pathOf("orthowarn.gltf") +
              ": camera 0 is orthographic; it is drawn in perspective with the default field of view");
}

// tinygltf skips an optional property of the wrong type and the object keeps its default: a light
// with "intensity": "5" lit the scene as with 1, with no word.
TEST_CASE("glTF errors: an optional property of the wrong type is refused by name") {
    const std::string kInteger =
        "expected an integer written without a fraction (tinygltf drops 1.0 as it drops \"1\")";
    checkErrors({
        {"intensitystr.gltf", [](json& g) { addLight(g, R"({"type": "point", "intensity": "5"})"); },
         "light 0: intensity is \"5\", expected a number"},
        {"colorstr.gltf", [](json& g) { addLight(g, R"({"type": "point", "color": ["1", 0, 0]})"); },
         "light 0: color is [\"1\",0,0], expected an array of 3 numbers"},
        {"conestr.gltf", [](json& g) { addLight(g, R"({"type": "spot", "spot": {"outerConeAngle": "1"}})"); },
         "light 0: spot.outerConeAngle is \"1\", expected a number"},
        {"translationstr.gltf", [](json& g) { g["nodes"][0]["translation"] = "1 2 3"; },
         "node 0: translation is \"1 2 3\", expected an array of 3 numbers"},
        {"meshfloat.gltf", [](json& g) { g["nodes"][0]["mesh"] = 0.5; }, "node 0: mesh is 0.5, " + kInteger},
        {"basecolorstr.gltf",
         [](json& g) {
             g["materials"] =
                 json::parse(R"([{"name": "m", "pbrMetallicRoughness": {"baseColorFactor": "red"}}])");
         },
         "material 0 'm': pbrMetallicRoughness.baseColorFactor is \"red\", expected an array of 4 numbers"},
        {"normalscale.gltf",
         [](json& g) { g["materials"] = json::parse(R"([{"normalTexture": {"index": 0, "scale": "2"}}])"); },
         "material 0: normalTexture.scale is \"2\", expected a number"},
        {"indicesfloat.gltf", [](json& g) { g["meshes"][0]["primitives"][0]["indices"] = 1.0; },
         "mesh 0 'tri' primitive 0: indices is 1.0, " + kInteger},
        {"offsetfloat.gltf", [](json& g) { g["accessors"][0]["byteOffset"] = 0.0; },
         "accessor 0: byteOffset is 0.0, " + kInteger},
        {"yfovstr.gltf",
         [](json& g) {
             addCamera(
                 g,
                 R"({"type": "perspective", "perspective": {"yfov": 1, "znear": 0.1, "aspectRatio": "1"}})");
         },
         "camera 0: perspective.aspectRatio is \"1\", expected a number"},
    });
    // tinygltf skips an index written as 0.0 too (the triangle's node lost its mesh).
    json whole = triangle();
    whole["nodes"][0]["mesh"] = 0.0;
    CHECK(gltfErrorOf("meshwhole.gltf", whole) ==
          pathOf("meshwhole.gltf") + ": node 0: mesh is 0.0, " + kInteger);
    // The same types in a binary glTF's JSON chunk.
    json wrong = triangle();
    wrong["nodes"][0]["scale"] = json::array({1, "1", 1});
    std::string chunk = wrong.dump();
    chunk.append((4 - chunk.size() % 4) % 4, ' ');
    const auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    const std::string glb = pathOf("scalestr.glb");
    std::ofstream(glb, std::ios::binary) << "glTF" << u32(2) << u32(uint32_t(20 + chunk.size()))
                                         << u32(uint32_t(chunk.size())) << "JSON" << chunk;
    CHECK(gltfErrorOf(glb) == glb + ": node 0: scale is [1,\"1\",1], expected an array of 3 numbers");
}

// tinygltf quotes the buffer's whole data URI when it cannot decode it: megabytes of base64 in one
// error line. The message keeps its start.
TEST_CASE("glTF errors: a data URI quoted in an error is cut short") {
    json g = triangle();
    g["buffers"][0]["byteLength"] = g["buffers"][0]["byteLength"].get<int>() + 4000;
    std::string uri = g["buffers"][0]["uri"];
    const std::string error = gltfErrorOf("bytelength.gltf", g);
    INFO(error);
    CHECK(error.find("Failed to decode 'uri'") != std::string::npos);
    CHECK(error.find(uri.substr(0, 48) + "... (" + std::to_string(uri.size()) + " characters)") !=
          std::string::npos);
}

namespace {

// The triangle's JSON text with `member` (raw JSON text, `"name": value`) added first.
std::string triangleWith(const std::string& member) {
    return "{" + member + "," + triangle().dump().substr(1);
}

// A GLB holding `chunk` as its JSON chunk (padded with spaces), with `version` in its header.
void writeGlb(const std::string& path, std::string chunk, uint32_t version = 2) {
    chunk.append((4 - chunk.size() % 4) % 4, ' ');
    const auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    std::ofstream(path, std::ios::binary) << "glTF" << u32(version) << u32(uint32_t(20 + chunk.size()))
                                          << u32(uint32_t(chunk.size())) << "JSON" << chunk;
}

} // namespace

// 15,000 nested arrays in "extras" (30 KB) overflowed the stack inside the JSON parser. The depth is
// counted before any parser sees the text; brackets inside strings are not nesting.
TEST_CASE("glTF errors: JSON nested thousands deep is refused before it is parsed") {
    for (const size_t depth : {size_t(15000), size_t(100000)}) {
        INFO("depth: " << depth);
        const std::string arrays = std::string(depth, '[') + std::string(depth, ']');
        const std::string path = pathOf("deeparrays.gltf");
        std::ofstream(path, std::ios::binary) << triangleWith("\"extras\": " + arrays);
        // The root object is level 1: the 256th '[' is too deep, byte 11 + 255 ("{\"extras\": " first).
        CHECK(gltfErrorOf(path) == path + ": JSON nested deeper than 256 levels (at byte 266); no glTF "
                                          "needs more, so the file is refused");
        std::string objects;
        for (size_t i = 0; i < depth; ++i)
            objects += "{\"a\":";
        objects += "0" + std::string(depth, '}');
        const std::string objectsPath = pathOf("deepobjects.gltf");
        std::ofstream(objectsPath, std::ios::binary) << triangleWith("\"extras\": " + objects);
        CHECK(gltfErrorOf(objectsPath).starts_with(objectsPath + ": JSON nested deeper than 256 levels"));
        const std::string glb = pathOf("deep.glb");
        writeGlb(glb, triangleWith("\"extras\": " + arrays));
        // A GLB's byte counts from the file's start: its JSON chunk begins at byte 20.
        CHECK(gltfErrorOf(glb) == glb + ": JSON nested deeper than 256 levels (at byte 286); no glTF needs "
                                        "more, so the file is refused");
    }
    // 256 levels load; brackets in strings, with escaped quotes and backslashes, count for nothing.
    const std::string path = pathOf("brackets.gltf");
    std::ofstream(path, std::ios::binary)
        << triangleWith("\"extras\": [" + std::string(254, '[') + std::string(254, ']') +
                        ", \"\\\\\", \"\\\"[[\", \"" + std::string(20000, '[') + "\"]");
    CHECK(gltfErrorOf(path) == "(no error)");
}

// glTF forbids count 0; the reader bound a reference to element 0 of an empty vector (UBSan).
TEST_CASE("glTF errors: an accessor with count 0 names the accessor") {
    checkErrors({
        {"count0.gltf", [](json& g) { g["accessors"][0]["count"] = 0; },
         "accessor 0: count is 0; glTF requires at least 1"},
        {"indexcount0.gltf", [](json& g) { g["accessors"][1]["count"] = 0; },
         "accessor 1: count is 0; glTF requires at least 1"},
    });
}

TEST_CASE("glTF errors: glTF 1.0 files are named as such") {
    const std::string hint = "; convert it to glTF 2.0";
    checkErrors({
        {"v10.gltf", [](json& g) { g["asset"]["version"] = "1.0"; },
         "glTF 1.0 is not supported (asset.version 1.0)" + hint},
        {"v1scene.gltf",
         [](json& g) {
             g.erase("asset");
             g["scene"] = "defaultScene";
         },
         "glTF 1.0 is not supported (\"scene\" is the string \"defaultScene\")" + hint},
        {"noasset.gltf", [](json& g) { g.erase("asset"); },
         "glTF 1.0 is not supported (no \"asset\" object, which glTF 2.0 requires)" + hint},
    });
    const std::string glb = pathOf("v1.glb");
    writeGlb(glb, R"({"scene": "defaultScene", "scenes": {"defaultScene": {"nodes": []}}})", 1);
    CHECK(gltfErrorOf(glb) == glb + ": glTF 1.0 is not supported (binary glTF version 1)" + hint);
}

// Draco's accessors have no bufferView: the extension is named before any accessor is looked at.
TEST_CASE("glTF errors: a required extension the engine lacks is named before the accessors") {
    checkErrors({
        {"draco.gltf",
         [](json& g) {
             g["extensionsUsed"] = {"KHR_draco_mesh_compression"};
             g["extensionsRequired"] = {"KHR_draco_mesh_compression"};
             g["accessors"][0].erase("bufferView");
             g["accessors"][1]["bufferView"] = 9;
         },
         "requires extension 'KHR_draco_mesh_compression', which LPV Engine does not support"},
        {"quantized.gltf",
         [](json& g) {
             g["extensionsRequired"] = {"KHR_lights_punctual", "KHR_mesh_quantization"};
             g["accessors"][0]["componentType"] = 5121;
         },
         "requires extension 'KHR_mesh_quantization', which LPV Engine does not support"},
    });
}

TEST_CASE("glTF errors: primitives written as an object, and negative texture indices") {
    checkErrors({
        {"primobject.gltf", [](json& g) { g["meshes"][0]["primitives"] = g["meshes"][0]["primitives"][0]; },
         "mesh 0 'tri': primitives must be an array (of primitive objects), not an object"},
        {"basecolor-1.gltf",
         [](json& g) {
             g["materials"] = json::parse(
                 R"([{"name": "paint", "pbrMetallicRoughness": {"baseColorTexture": {"index": -1}}}])");
         },
         "material 0 'paint': pbrMetallicRoughness.baseColorTexture.index is -1, expected an index (an "
         "integer, 0 or more)"},
        {"normal-5.gltf",
         [](json& g) { g["materials"] = json::parse(R"([{"normalTexture": {"index": -5}}])"); },
         "material 0: normalTexture.index is -5, expected an index (an integer, 0 or more)"},
        {"emissive9.gltf",
         [](json& g) { g["materials"] = json::parse(R"([{"emissiveTexture": {"index": 9}}])"); },
         "material 0: emissiveTexture refers to texture 9, which does not exist"},
    });
}

// A 1 MB string was echoed whole in the error.
TEST_CASE("glTF errors: a very long value echoed in an error is cut short") {
    const std::string name(1 << 20, 'n');
    const std::string cut = std::string(80, 'n') + "... (1048576 bytes)";
    checkErrors({
        {"longversion.gltf", [&](json& g) { g["asset"]["version"] = name; },
         "asset version '" + cut + "' is not supported (glTF 2.x only)"},
        {"longmesh.gltf",
         [&](json& g) {
             g["meshes"][0]["name"] = name;
             g["meshes"][0]["primitives"][0]["material"] = 7;
         },
         "mesh 0 '" + cut + "' primitive 0 refers to material 7, which does not exist"},
        {"longtype.gltf", [&](json& g) { addLight(g, R"({"type": ")" + name + R"("})"); },
         "light 0: type '" + cut + "' is not directional, point or spot"},
        {"longstr.gltf",
         [&](json& g) { addLight(g, R"({"type": "point", "intensity": ")" + name + R"("})"); },
         "light 0: intensity is \"" + std::string(79, 'n') + "... (1048578 bytes), expected a number"},
    });
}
