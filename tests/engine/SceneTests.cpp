// Scenes: the built-in ones build with the expected contents; glTF files written by this test load,
// and each kind of broken file gives an error naming the file and the problem.
#include "GltfErrorOf.h"
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/SceneLoading.h"
#include "platforms/Log.h"

#include <doctest/doctest.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

using namespace lpv;
using namespace lpv::engine;

namespace {

using lpv::test::gltfErrorOf;

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t n = (uint32_t(bytes[i]) << 16) |
                           (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        out += kAlphabet[(n >> 18) & 63];
        out += kAlphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? kAlphabet[(n >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kAlphabet[n & 63] : '=';
    }
    return out;
}

// A unit quad in the xy plane (4 positions, 6 uint16 indices), as a glTF buffer.
struct QuadBuffer {
    std::vector<uint8_t> bytes;
    static constexpr size_t kPositionBytes = 4 * 12;
    static constexpr size_t kIndexBytes = 6 * 2;
};

QuadBuffer quadBuffer(float firstX = 0.0f, uint16_t lastIndex = 3) {
    const float positions[12] = {firstX, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, lastIndex};
    QuadBuffer b;
    b.bytes.resize(QuadBuffer::kPositionBytes + QuadBuffer::kIndexBytes);
    std::memcpy(b.bytes.data(), positions, sizeof(positions));
    std::memcpy(b.bytes.data() + sizeof(positions), indices, sizeof(indices));
    return b;
}

struct GltfOptions {
    std::string bufferUri; // empty: embedded data URI
    std::string extensionsRequired = "";
    std::string imageUri = ""; // non-empty: the material gets a base color texture from this image
    std::string material = ""; // more of the material's members (from ", ")
    bool baseColorMap = true;  // false: the image is there for `material`'s maps only
};

std::string gltfJson(const QuadBuffer& buffer, const GltfOptions& o = {}) {
    const std::string uri =
        o.bufferUri.empty() ? "data:application/octet-stream;base64," + base64(buffer.bytes) : o.bufferUri;
    std::string texture =
        o.imageUri.empty() || !o.baseColorMap ? "" : R"(, "baseColorTexture": {"index": 0})";
    std::string images =
        o.imageUri.empty() ? ""
                           : R"(, "images": [{"uri": ")" + o.imageUri + R"("}], "textures": [{"source": 0}])";
    std::string required =
        o.extensionsRequired.empty() ? "" : R"(, "extensionsRequired": [")" + o.extensionsRequired + R"("])";
    return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_lights_punctual"])" +
           required + R"(,
  "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.5, 0.25], "intensity": 40}]}},
  "scene": 0,
  "scenes": [{"nodes": [0, 2, 3]}],
  "nodes": [
    {"name": "parent", "translation": [10, 0, 0], "children": [1]},
    {"name": "quad", "mesh": 0, "scale": [2, 2, 2]},
    {"name": "camera", "camera": 0, "translation": [0, 1, 5]},
    {"name": "lamp", "translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}
  ],
  "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 50, "aspectRatio": 1.5}}],
  "meshes": [{"name": "quad", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
  "materials": [{"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.2, 0.1, 1], "metallicFactor": 0, "roughnessFactor": 0.4)" +
           texture + R"(})" + o.material + R"(}],
  "buffers": [{"byteLength": )" +
           std::to_string(buffer.bytes.size()) + R"(, "uri": ")" + uri + R"("}],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 12}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ])" + images +
           "}";
}

std::string write(const std::string& name, const std::string& text) {
    const std::string path = "/tmp/lpv_scenetest_" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// `path` loaded, and the warnings the loader logged meanwhile (the sink is restored either way).
struct LoadedWithWarnings {
    Scene scene;
    std::vector<std::string> warnings;
};
LoadedWithWarnings loadWithWarnings(const std::string& path) {
    LoadedWithWarnings out;
    auto previous = log::setSink([&](log::Level level, std::string_view m) {
        if (level == log::Level::Warning) out.warnings.emplace_back(m);
    });
    struct Restore {
        log::Sink sink;
        ~Restore() { log::setSink(std::move(sink)); }
    } restore{std::move(previous)};
    out.scene = loadGltf(path);
    return out;
}

} // namespace

TEST_CASE("scenes: the Cornell box") {
    const Scene s = buildCornellBox();
    CHECK(s.name == "cornell");
    CHECK(s.meshes.size() == 7);
    CHECK(s.instances.size() == 7);
    CHECK(s.triangleCount() == 120); // 10 slabs and 2 boxes, 12 triangles each
    CHECK(s.materials.size() == 4);
    CHECK(s.materials[1].baseColor.r > 5 * s.materials[1].baseColor.g); // red wall
    CHECK(s.materials[2].baseColor.g > 3 * s.materials[2].baseColor.r); // green wall
    REQUIRE(s.lights.size() == 1);
    CHECK(s.lights[0].type == LightType::Directional);
    CHECK(s.lights[0].direction.y < -0.85f);
    REQUIRE(s.camera.has_value());
    CHECK(s.bounds.min.y == doctest::Approx(-0.1f));
    CHECK(s.bounds.max.y == doctest::Approx(5.6f));
    for (const Vertex& v : s.vertices)
        REQUIRE(glm::length(v.normal) == doctest::Approx(1.0f).epsilon(1e-4));
    for (uint32_t i : s.indices)
        REQUIRE(i < s.vertices.size());
    CHECK(loadScene("cornell").triangleCount() == 120);
}

TEST_CASE("scenes: a box is outside a view's clip volume only when it lies beyond one of its planes") {
    // An orthographic view of x, y in [-1, 1] and z in [-1, -5] (looking down -z from the origin),
    // and a perspective one of 90 degrees, near 0.5, far 10.
    const glm::mat4 ortho = glm::orthoRH_ZO(-1.0f, 1.0f, -1.0f, 1.0f, 1.0f, 5.0f);
    const glm::mat4 perspective = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, 0.5f, 10.0f);
    const auto box = [](glm::vec3 lo, glm::vec3 hi) {
        Bounds b;
        b.add(lo);
        b.add(hi);
        return b;
    };
    CHECK(!box({-0.5f, -0.5f, -3.0f}, {0.5f, 0.5f, -2.0f}).outsideClipVolume(ortho)); // inside
    CHECK(!box({0.5f, -0.5f, -3.0f}, {3.0f, 0.5f, -2.0f}).outsideClipVolume(ortho));  // straddles x = 1
    CHECK(box({1.5f, -0.5f, -3.0f}, {3.0f, 0.5f, -2.0f}).outsideClipVolume(ortho));   // beyond x = 1
    CHECK(box({-0.5f, -3.0f, -3.0f}, {0.5f, -1.5f, -2.0f}).outsideClipVolume(ortho)); // below y = -1
    CHECK(box({-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}).outsideClipVolume(ortho));   // before the near plane
    CHECK(box({-0.5f, -0.5f, -9.0f}, {0.5f, 0.5f, -6.0f}).outsideClipVolume(ortho));  // past the far plane
    CHECK(!box({-9.0f, -9.0f, -9.0f}, {9.0f, 9.0f, 9.0f}).outsideClipVolume(ortho));  // around it all
    CHECK(Bounds{}.outsideClipVolume(ortho));                                         // empty
    // Perspective: a box at depth 5 inside the 90-degree cone, one beside it, one behind the eye.
    CHECK(!box({3.0f, -1.0f, -6.0f}, {4.0f, 1.0f, -5.0f}).outsideClipVolume(perspective));
    CHECK(box({6.0f, -1.0f, -5.0f}, {7.0f, 1.0f, -4.0f}).outsideClipVolume(perspective));
    CHECK(box({-1.0f, -1.0f, 1.0f}, {1.0f, 1.0f, 2.0f}).outsideClipVolume(perspective));
}

TEST_CASE("scenes: a glTF file written here loads with transforms, material, camera and light") {
    const std::string path = write("good.gltf", gltfJson(quadBuffer()));
    const Scene s = loadGltf(path);
    REQUIRE(s.meshes.size() == 1);
    REQUIRE(s.instances.size() == 1);
    CHECK(s.triangleCount() == 2);
    // parent translation (10,0,0) then scale 2: the quad spans x in [10, 12].
    CHECK(s.bounds.min.x == doctest::Approx(10.0f));
    CHECK(s.bounds.max.x == doctest::Approx(12.0f));
    CHECK(s.bounds.max.y == doctest::Approx(2.0f));
    REQUIRE(s.materials.size() == 1);
    CHECK(s.materials[0].baseColor.r == doctest::Approx(0.9f));
    CHECK(s.materials[0].roughness == doctest::Approx(0.4f));
    // Normals computed (the file has none) face +z.
    CHECK(s.vertices[0].normal.z == doctest::Approx(1.0f));
    REQUIRE(s.camera.has_value());
    CHECK(s.camera->position.z == doctest::Approx(5.0f));
    CHECK(s.camera->verticalFov == doctest::Approx(0.9f));
    CHECK(s.camera->forward.z == doctest::Approx(-1.0f));
    REQUIRE(s.lights.size() == 1);
    CHECK(s.lights[0].type == LightType::Point);
    CHECK(s.lights[0].intensity == doctest::Approx(40.0f));
    CHECK(s.lights[0].position.y == doctest::Approx(3.0f));
    CHECK(loadScene(path).triangleCount() == 2);
}

TEST_CASE("scenes: a .glb with an external buffer file loads") {
    const QuadBuffer buffer = quadBuffer();
    {
        std::ofstream bin("/tmp/lpv_scenetest_quad.bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(buffer.bytes.data()), std::streamsize(buffer.bytes.size()));
    }
    std::string json = gltfJson(buffer, {"lpv_scenetest_quad.bin"});
    while (json.size() % 4)
        json += ' ';
    std::string glb = "glTF";
    const auto u32 = [&](uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
    u32(2);
    u32(uint32_t(12 + 8 + json.size()));
    u32(uint32_t(json.size()));
    u32(0x4E4F534Au); // "JSON"
    glb += json;
    const std::string path = write("quad.glb", glb);
    CHECK(loadGltf(path).triangleCount() == 2);
}

TEST_CASE("scenes: a truncated file is an error naming the file") {
    const std::string full = gltfJson(quadBuffer());
    const std::string path = write("truncated.gltf", full.substr(0, full.size() / 2));
    const std::string e = gltfErrorOf(path);
    CHECK(e.find(path + ": not a valid glTF 2.0 file") == 0);
}

TEST_CASE("scenes: a missing buffer is an error naming the file") {
    const std::string path = write("nobuffer.gltf", gltfJson(quadBuffer(), {"does_not_exist.bin"}));
    const std::string e = gltfErrorOf(path);
    CHECK(e.find(path + ": ") == 0);
    CHECK(e.find("does_not_exist.bin") != std::string::npos);
}

TEST_CASE("scenes: out-of-range indices are an error") {
    const std::string path = write("badindex.gltf", gltfJson(quadBuffer(0.0f, 7)));
    CHECK(gltfErrorOf(path) ==
          path + ": mesh 0 'quad' primitive 0: index 7 at position 5 is out of range (4 vertices)");
}

TEST_CASE("scenes: NaN positions are an error") {
    const std::string path = write("nan.gltf", gltfJson(quadBuffer(std::numeric_limits<float>::quiet_NaN())));
    CHECK(gltfErrorOf(path) ==
          path + ": mesh 0 'quad' primitive 0: vertex 0 has a non-finite position (NaN or infinity)");
}

TEST_CASE("scenes: an unsupported extension marked required is an error") {
    const std::string path = write("draco.gltf", gltfJson(quadBuffer(), {"", "KHR_draco_mesh_compression"}));
    CHECK(gltfErrorOf(path) ==
          path + ": requires extension 'KHR_draco_mesh_compression', which LPV Engine does not support");
}

TEST_CASE("scenes: a missing texture warns and falls back to the flat color") {
    const std::string path = write("notexture.gltf", gltfJson(quadBuffer(), {"", "", "nothere.png"}));
    const auto [s, warnings] = loadWithWarnings(path);
    CHECK(s.materials[0].baseColorTexture == -1);
    CHECK(s.materials[0].baseColor.r == doctest::Approx(0.9f));
    bool named = false;
    for (const auto& w : warnings)
        named = named || (w.find(path) == 0 && w.find("nothere.png") != std::string::npos);
    CHECK_MESSAGE(named, "no warning naming the file and the texture");
}

// Image data that cannot be decoded is handled as a missing image: it used to end the load
// (exit 2) where a missing file only warned.
TEST_CASE("scenes: an image that cannot be decoded warns and falls back to the flat color") {
    const std::string notPng = "data:image/png;base64,bm90IGEgcG5nIGF0IGFsbA=="; // "not a png at all"
    const std::string path = write("badimage.gltf", gltfJson(quadBuffer(), {"", "", notPng}));
    const auto [s, warnings] = loadWithWarnings(path);
    CHECK(s.materials[0].baseColorTexture == -1);
    CHECK(s.materials[0].baseColor.r == doctest::Approx(0.9f));
    bool fellBack = false, named = false;
    for (const auto& w : warnings) {
        fellBack = fellBack || (w.find(path) == 0 && w.find("uses its flat factor") != std::string::npos);
        named = named || (w.find(path) == 0 && w.find("image 0 cannot be decoded") != std::string::npos);
    }
    CHECK_MESSAGE(fellBack, "no warning naming the material's fallback");
    CHECK_MESSAGE(named, "no warning naming the image that cannot be decoded");
}

TEST_CASE("scenes: an optional extension the reader does not know is named in a warning") {
    std::string json = gltfJson(quadBuffer());
    const std::string used = R"("extensionsUsed": ["KHR_lights_punctual"])";
    REQUIRE(json.find(used) != std::string::npos);
    json.replace(json.find(used), used.size(),
                 R"("extensionsUsed": ["KHR_lights_punctual", "KHR_texture_transform"])");
    const std::string path = write("transform.gltf", json);
    const auto [s, warnings] = loadWithWarnings(path);
    CHECK(s.materials.size() == 1);
    bool named = false, lights = false;
    for (const auto& w : warnings) {
        named = named || (w.find(path) == 0 &&
                          w.find("'KHR_texture_transform', which LPV Engine ignores") != std::string::npos);
        lights = lights || w.find("KHR_lights_punctual") != std::string::npos;
    }
    CHECK_MESSAGE(named, "no warning naming the file and the extension");
    CHECK_FALSE(lights); // a supported extension is not reported
}

TEST_CASE("scenes: an emissive map is read, and an occlusion map is named as unused") {
    // The emissive map's image is missing: the reader tries it, warns and keeps the flat factor.
    const std::string path =
        write("maps.gltf",
              gltfJson(quadBuffer(), {"", "", "glow.png",
                                      R"(, "emissiveFactor": [1, 0.5, 0], "emissiveTexture": {"index": 0},
                                                     "occlusionTexture": {"index": 0})",
                                      false}));
    const auto [s, warnings] = loadWithWarnings(path);
    CHECK(s.materials[0].emissiveTexture == -1);
    CHECK(s.materials[0].emissive.g == doctest::Approx(0.5f));
    bool triedEmissive = false, namedOcclusion = false;
    for (const auto& w : warnings) {
        triedEmissive = triedEmissive ||
                        (w.find("glow.png") != std::string::npos && w.find("'paint'") != std::string::npos);
        namedOcclusion =
            namedOcclusion ||
            (w.find(path) == 0 && w.find("'paint': occlusionTexture is not used") != std::string::npos);
    }
    CHECK_MESSAGE(triedEmissive, "no warning naming the emissive map's image");
    CHECK_MESSAGE(namedOcclusion, "no warning naming the unused occlusion map");
}

TEST_CASE("scenes: an emissive map that loads is kept as an sRGB texture") {
    // A 1x1 PNG of (255, 128, 0), embedded as a data URI.
    const std::string png =
        "data:image/png;base64,"
        "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP438AAAAQBAYDFKhhdAAAAAElFTkSuQmCC";
    const std::string path = write(
        "emissive.gltf",
        gltfJson(quadBuffer(),
                 {"", "", png, R"(, "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0})", false}));
    const Scene s = loadGltf(path);
    REQUIRE(s.materials[0].emissiveTexture >= 0);
    CHECK(s.materials[0].baseColorTexture == -1);
    const TextureImage& map = s.textures.at(size_t(s.materials[0].emissiveTexture));
    CHECK(map.srgb);
    REQUIRE(map.width == 1);
    REQUIRE(map.rgba.size() == 4);
    CHECK(map.rgba[0] == 255);
    CHECK(map.rgba[1] == 128);
    CHECK(map.rgba[2] == 0);
}

TEST_CASE("scenes: a blended material and a map on a second texture set are named, not dropped unnoticed") {
    const std::string path =
        write("blend.gltf",
              gltfJson(quadBuffer(),
                       {"", "", "nothere.png",
                        R"(, "alphaMode": "BLEND", "normalTexture": {"index": 0, "texCoord": 1})", false}));
    const auto [s, warnings] = loadWithWarnings(path);
    CHECK(s.materials.size() == 1);
    bool blend = false, texCoord = false, noTexCoords = false;
    for (const auto& w : warnings) {
        // The quad has no texture coordinates at all: its maps are read at one texel.
        noTexCoords =
            noTexCoords || w == path + ": mesh 0 'quad' primitive 0: material 0 'paint' has texture maps but "
                                       "the primitive has no TEXCOORD_0; each map is read at its first texel";
        blend = blend || w == path + ": material 0 'paint': alphaMode BLEND is drawn as OPAQUE";
        texCoord =
            texCoord ||
            w == path + ": material 0 'paint': normalTexture names TEXCOORD_1; it is read through TEXCOORD_0";
    }
    CHECK_MESSAGE(blend, "no warning for the blended material");
    CHECK_MESSAGE(texCoord, "no warning for the second texture set");
    CHECK_MESSAGE(noTexCoords, "no warning for maps on a primitive without texture coordinates");
}

TEST_CASE("scenes: a file that does not exist") {
    CHECK(gltfErrorOf("/nonexistent/scene.gltf") ==
          "/nonexistent/scene.gltf: cannot open the file: No such file or directory");
}

// A misspelt built-in scene read as a missing file, with no word of the built-in names.
TEST_CASE("scenes: a scene name that is neither built in nor a file lists the built-in ones") {
    const auto errorOf = [](const std::string& name) {
        try {
            (void)loadScene(name);
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    CHECK(errorOf("cornel") ==
          "cornel: neither a built-in scene (cornell, atrium, lights) nor a file: No such file or directory");
    CHECK(errorOf("") == "'': neither a built-in scene (cornell, atrium, lights) nor a file");
}
