// Optional glTF properties of the wrong type: refused by name instead of silently defaulted.
#include "GltfJsonTypes.h"

#include "engine/scene/SceneLoading.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <span>

namespace lpv::engine {
namespace {

using json = nlohmann::json;

enum class Kind { Number, Integer, String, Boolean, Numbers, Integers, Object };

// A property and, for an object, its own properties. `count` is an array's length (0: any).
struct Property {
    const char* name;
    Kind kind;
    size_t count = 0;
    std::span<const Property> members = {};
};

constexpr Property kTextureInfo[] = {{"index", Kind::Integer}, {"texCoord", Kind::Integer}};
constexpr Property kNormalTexture[] = {
    {"index", Kind::Integer}, {"texCoord", Kind::Integer}, {"scale", Kind::Number}};
constexpr Property kOcclusionTexture[] = {
    {"index", Kind::Integer}, {"texCoord", Kind::Integer}, {"strength", Kind::Number}};
constexpr Property kPbr[] = {{"baseColorFactor", Kind::Numbers, 4},
                             {"baseColorTexture", Kind::Object, 0, kTextureInfo},
                             {"metallicFactor", Kind::Number},
                             {"roughnessFactor", Kind::Number},
                             {"metallicRoughnessTexture", Kind::Object, 0, kTextureInfo}};
constexpr Property kMaterial[] = {{"name", Kind::String},
                                  {"pbrMetallicRoughness", Kind::Object, 0, kPbr},
                                  {"normalTexture", Kind::Object, 0, kNormalTexture},
                                  {"occlusionTexture", Kind::Object, 0, kOcclusionTexture},
                                  {"emissiveTexture", Kind::Object, 0, kTextureInfo},
                                  {"emissiveFactor", Kind::Numbers, 3},
                                  {"alphaMode", Kind::String},
                                  {"alphaCutoff", Kind::Number},
                                  {"doubleSided", Kind::Boolean}};
constexpr Property kNodeLight[] = {{"light", Kind::Integer}};
constexpr Property kNodeExtensions[] = {{"KHR_lights_punctual", Kind::Object, 0, kNodeLight}};
constexpr Property kNode[] = {{"name", Kind::String},
                              {"camera", Kind::Integer},
                              {"mesh", Kind::Integer},
                              {"children", Kind::Integers},
                              {"matrix", Kind::Numbers, 16},
                              {"rotation", Kind::Numbers, 4},
                              {"scale", Kind::Numbers, 3},
                              {"translation", Kind::Numbers, 3},
                              {"extensions", Kind::Object, 0, kNodeExtensions}};
constexpr Property kPerspective[] = {
    {"aspectRatio", Kind::Number}, {"yfov", Kind::Number}, {"zfar", Kind::Number}, {"znear", Kind::Number}};
constexpr Property kOrthographic[] = {
    {"xmag", Kind::Number}, {"ymag", Kind::Number}, {"zfar", Kind::Number}, {"znear", Kind::Number}};
constexpr Property kCamera[] = {{"name", Kind::String},
                                {"type", Kind::String},
                                {"perspective", Kind::Object, 0, kPerspective},
                                {"orthographic", Kind::Object, 0, kOrthographic}};
constexpr Property kSpot[] = {{"innerConeAngle", Kind::Number}, {"outerConeAngle", Kind::Number}};
constexpr Property kLight[] = {{"name", Kind::String},      {"type", Kind::String},
                               {"color", Kind::Numbers, 3}, {"intensity", Kind::Number},
                               {"range", Kind::Number},     {"spot", Kind::Object, 0, kSpot}};
constexpr Property kScene[] = {{"name", Kind::String}, {"nodes", Kind::Integers}};
constexpr Property kPrimitive[] = {
    {"indices", Kind::Integer}, {"material", Kind::Integer}, {"mode", Kind::Integer}};
constexpr Property kAccessor[] = {
    {"bufferView", Kind::Integer}, {"byteOffset", Kind::Integer}, {"normalized", Kind::Boolean}};
constexpr Property kBufferView[] = {
    {"byteOffset", Kind::Integer}, {"byteStride", Kind::Integer}, {"target", Kind::Integer}};
constexpr Property kTexture[] = {{"source", Kind::Integer}, {"sampler", Kind::Integer}};

std::string expected(const Property& p) {
    switch (p.kind) {
    case Kind::Number:
        return "a number";
    case Kind::Integer:
        return "an integer written without a fraction (tinygltf drops 1.0 as it drops \"1\")";
    case Kind::String:
        return "a string";
    case Kind::Boolean:
        return "true or false";
    case Kind::Numbers:
        return p.count ? "an array of " + std::to_string(p.count) + " numbers" : "an array of numbers";
    case Kind::Integers:
        return "an array of integers written without a fraction";
    case Kind::Object:
        return "an object";
    }
    return "?";
}

// Written without a fraction: tinygltf skips 1.0 where it wants an index, as it does "1".
bool isInteger(const json& v) {
    return v.is_number_integer();
}

bool holds(const json& v, const Property& p) {
    const auto all = [&](auto test) {
        // A wrong length is GltfValidation's to name ("scale has 2 numbers, expected 3").
        if (!v.is_array()) return false;
        for (const json& e : v)
            if (!test(e)) return false;
        return true;
    };
    switch (p.kind) {
    case Kind::Number:
        return v.is_number();
    case Kind::Integer:
        return isInteger(v);
    case Kind::String:
        return v.is_string();
    case Kind::Boolean:
        return v.is_boolean();
    case Kind::Numbers:
        return all([](const json& e) { return e.is_number(); });
    case Kind::Integers:
        return all([](const json& e) { return isInteger(e); });
    case Kind::Object:
        return v.is_object();
    }
    return false;
}

std::string shown(const json& v) {
    std::string text = v.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

void checkObject(const std::string& path, const json& object, std::span<const Property> properties,
                 const std::string& who, const std::string& prefix) {
    for (const Property& p : properties) {
        const auto it = object.find(p.name);
        if (it == object.end()) continue;
        const std::string name = prefix + p.name;
        if (!holds(*it, p))
            throw SceneError(path, who + ": " + name + " is " + shown(*it) + ", expected " + expected(p));
        if (p.kind == Kind::Object) checkObject(path, *it, p.members, who, name + ".");
    }
}

// Each element of the array `key` of `parent`, named "<what> <index> '<name>'" as the other checks do.
void checkArray(const std::string& path, const json& parent, const char* key, const char* what,
                std::span<const Property> properties,
                const std::function<void(const json&, const std::string&)>& more = nullptr) {
    const auto it = parent.find(key);
    if (it == parent.end() || !it->is_array()) return; // tinygltf has refused a non-array
    for (size_t i = 0; i < it->size(); ++i) {
        const json& element = (*it)[i];
        if (!element.is_object()) continue;
        std::string who = std::string(what) + " " + std::to_string(i);
        if (const auto name = element.find("name"); name != element.end() && name->is_string())
            who += " '" + name->get<std::string>() + "'";
        checkObject(path, element, properties, who, "");
        if (more) more(element, who);
    }
}

std::string jsonText(const std::string& path, bool binary) {
    std::ifstream file(path, std::ios::binary);
    if (!binary) return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    // GLB: a 12-byte header, then the JSON chunk's length and type, then the JSON (tinygltf has
    // checked this layout already). Only that chunk is read, not the binary one after it.
    char head[20] = {};
    if (!file.read(head, sizeof(head))) return "{}";
    uint32_t length = 0;
    std::memcpy(&length, head + 12, 4);
    std::string text(length, '\0');
    file.read(text.data(), std::streamsize(length));
    text.resize(size_t(file.gcount()));
    return text;
}

} // namespace

void checkGltfJsonTypes(const std::string& path, bool binary) {
    const json gltf = json::parse(jsonText(path, binary), nullptr, false);
    if (!gltf.is_object()) return; // tinygltf read it; nothing here to add
    checkArray(path, gltf, "nodes", "node", kNode);
    checkArray(path, gltf, "materials", "material", kMaterial);
    checkArray(path, gltf, "cameras", "camera", kCamera);
    checkArray(path, gltf, "scenes", "scene", kScene);
    checkArray(path, gltf, "accessors", "accessor", kAccessor);
    checkArray(path, gltf, "bufferViews", "bufferView", kBufferView);
    checkArray(path, gltf, "textures", "texture", kTexture);
    checkArray(path, gltf, "meshes", "mesh", {}, [&](const json& mesh, const std::string& who) {
        checkArray(path, mesh, "primitives", (who + " primitive").c_str(), kPrimitive);
    });
    if (const auto scene = gltf.find("scene"); scene != gltf.end() && !isInteger(*scene))
        throw SceneError(path,
                         "scene is " + shown(*scene) + ", expected " + expected({"scene", Kind::Integer}));
    const json* lights = nullptr;
    if (const auto e = gltf.find("extensions"); e != gltf.end() && e->is_object())
        if (const auto k = e->find("KHR_lights_punctual"); k != e->end() && k->is_object()) lights = &*k;
    if (!lights) return;
    checkArray(path, *lights, "lights", "light", kLight, [&](const json& light, const std::string& who) {
        // An absent range is no limit; a given one must be positive (tinygltf reads both as 0).
        if (const auto range = light.find("range"); range != light.end() && !(range->get<double>() > 0.0))
            throw SceneError(path, who + ": range " + shown(*range) + " must be greater than 0");
    });
}

} // namespace lpv::engine
