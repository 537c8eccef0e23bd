// The glTF file's own JSON, checked before tinygltf reads it: nesting the parsers cannot take,
// glTF 1.0, required extensions the engine lacks, and optional properties of the wrong type (refused
// by name instead of silently defaulted).
#include "GltfJsonTypes.h"

#include "engine/config/ShownText.h"
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

const std::string kConvert = "convert it to glTF 2.0";

// Index and Indices: integers 0 or more (tinygltf reads -1 as "none" and loads without a word).
enum class Kind { Number, Integer, Index, String, Boolean, Numbers, Integers, Indices, Object };

// A property and, for an object, its own properties. `count` is an array's length (0: any).
struct Property {
    const char* name;
    Kind kind;
    size_t count = 0;
    std::span<const Property> members = {};
};

constexpr Property kTextureInfo[] = {{"index", Kind::Index}, {"texCoord", Kind::Index}};
constexpr Property kNormalTexture[] = {
    {"index", Kind::Index}, {"texCoord", Kind::Index}, {"scale", Kind::Number}};
constexpr Property kOcclusionTexture[] = {
    {"index", Kind::Index}, {"texCoord", Kind::Index}, {"strength", Kind::Number}};
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
constexpr Property kNodeLight[] = {{"light", Kind::Index}};
constexpr Property kNodeExtensions[] = {{"KHR_lights_punctual", Kind::Object, 0, kNodeLight}};
constexpr Property kNode[] = {{"name", Kind::String},
                              {"camera", Kind::Index},
                              {"mesh", Kind::Index},
                              {"children", Kind::Indices},
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
constexpr Property kScene[] = {{"name", Kind::String}, {"nodes", Kind::Indices}};
constexpr Property kPrimitive[] = {
    {"indices", Kind::Index}, {"material", Kind::Index}, {"mode", Kind::Integer}};
constexpr Property kAccessor[] = {
    {"bufferView", Kind::Index}, {"byteOffset", Kind::Integer}, {"normalized", Kind::Boolean}};
constexpr Property kBufferView[] = {
    {"byteOffset", Kind::Integer}, {"byteStride", Kind::Integer}, {"target", Kind::Integer}};
constexpr Property kTexture[] = {{"source", Kind::Index}, {"sampler", Kind::Index}};

constexpr const char* kIndexExpected = "an index (an integer, 0 or more)";

// Written without a fraction: tinygltf skips 1.0 where it wants an index, as it does "1".
bool isInteger(const json& v) {
    return v.is_number_integer();
}

// What `p` must be; `v`, the value found, tells a negative index from one that is not an integer.
std::string expected(const Property& p, const json& v = {}) {
    const auto negative = [](const json& e) { return e.is_number_integer() && e.get<int64_t>() < 0; };
    switch (p.kind) {
    case Kind::Number:
        return "a number";
    case Kind::Index:
        if (negative(v)) return kIndexExpected;
        [[fallthrough]];
    case Kind::Integer:
        return "an integer written without a fraction (tinygltf drops 1.0 as it drops \"1\")";
    case Kind::String:
        return "a string";
    case Kind::Boolean:
        return "true or false";
    case Kind::Numbers:
        return p.count ? "an array of " + std::to_string(p.count) + " numbers" : "an array of numbers";
    case Kind::Indices:
        if (v.is_array() && std::all_of(v.begin(), v.end(), [](const json& e) { return isInteger(e); }))
            return std::string("an array of indices (integers, 0 or more)");
        [[fallthrough]];
    case Kind::Integers:
        return "an array of integers written without a fraction";
    case Kind::Object:
        return "an object";
    }
    return "?";
}

bool isIndex(const json& v) {
    return isInteger(v) && v.get<int64_t>() >= 0;
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
    case Kind::Index:
        return isIndex(v);
    case Kind::String:
        return v.is_string();
    case Kind::Boolean:
        return v.is_boolean();
    case Kind::Numbers:
        return all([](const json& e) { return e.is_number(); });
    case Kind::Integers:
        return all([](const json& e) { return isInteger(e); });
    case Kind::Indices:
        return all([](const json& e) { return isIndex(e); });
    case Kind::Object:
        return v.is_object();
    }
    return false;
}

std::string shown(const json& v) {
    return shownText(v.dump());
}

void checkObject(const std::string& path, const json& object, std::span<const Property> properties,
                 const std::string& who, const std::string& prefix) {
    for (const Property& p : properties) {
        const auto it = object.find(p.name);
        if (it == object.end()) continue;
        const std::string name = prefix + p.name;
        if (!holds(*it, p))
            throw SceneError(path,
                             who + ": " + name + " is " + shown(*it) + ", expected " + expected(p, *it));
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
            who += " '" + shownText(name->get<std::string>()) + "'";
        checkObject(path, element, properties, who, "");
        if (more) more(element, who);
    }
}

// The file's JSON text: the whole file, or a GLB's JSON chunk, read no further than the file goes
// (tinygltf has not checked the layout yet: it is left to it to refuse a broken one).
std::string jsonText(const std::string& path, bool binary) {
    std::ifstream file(path, std::ios::binary);
    if (!binary) return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    // GLB: a 12-byte header (magic, version, length), then the JSON chunk's length and type, then the JSON.
    char head[20] = {};
    if (!file.read(head, sizeof(head))) return "";
    uint32_t version = 0, length = 0;
    std::memcpy(&version, head + 4, 4);
    std::memcpy(&length, head + 12, 4);
    if (version == 1)
        throw SceneError(path, "glTF 1.0 is not supported (binary glTF version 1); " + kConvert);
    file.seekg(0, std::ios::end);
    const auto size = std::streamoff(file.tellg());
    file.seekg(sizeof(head));
    std::string text(size_t(std::min<std::streamoff>(length, std::max<std::streamoff>(size - 20, 0))), '\0');
    file.read(text.data(), std::streamsize(text.size()));
    text.resize(size_t(file.gcount()));
    return text;
}

// Where `text` nests arrays and objects deeper than kMaxJsonDepth: the byte of the first bracket too
// deep, or npos. Brackets inside strings do not count; a string's escapes (\" and \\) are skipped.
size_t tooDeepAt(std::string_view text) {
    size_t depth = 0;
    bool inString = false;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) return i;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return std::string_view::npos;
}

// glTF 1.0 read as 2.0 fails on whatever differs first ("defaultScene", "asset object not found"):
// the version is named instead.
void refuseGltf1(const std::string& path, const json& gltf) {
    std::string reason;
    const auto asset = gltf.find("asset");
    const auto scene = gltf.find("scene");
    if (scene != gltf.end() && scene->is_string())
        reason = "\"scene\" is the string " + shown(*scene);
    else if (asset == gltf.end() || !asset->is_object())
        reason = "no \"asset\" object, which glTF 2.0 requires";
    else if (const auto version = asset->find("version"); version != asset->end() && version->is_string()) {
        const std::string v = version->get<std::string>();
        if (v == "1" || v.starts_with("1.")) reason = "asset.version " + shownText(v);
    }
    if (!reason.empty()) throw SceneError(path, "glTF 1.0 is not supported (" + reason + "); " + kConvert);
}

std::string withArticle(std::string_view type) {
    return (type == "object" || type == "array" ? "an " : "a ") + std::string(type);
}

} // namespace

void checkGltfJson(const std::string& path, bool binary, std::span<const char* const> supportedExtensions) {
    const std::string text = jsonText(path, binary);
    if (const size_t at = tooDeepAt(text); at != std::string_view::npos)
        throw SceneError(path, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                                   " levels (at byte " + std::to_string(at + (binary ? 20 : 0)) +
                                   "); no glTF needs more, so the file is refused");
    const json gltf = json::parse(text, nullptr, false);
    if (!gltf.is_object()) return; // tinygltf says what is wrong with it
    refuseGltf1(path, gltf);
    // Before anything else: what an extension changes (Draco's accessors have no bufferView) would
    // otherwise be reported as a broken file.
    if (const auto required = gltf.find("extensionsRequired"); required != gltf.end() && required->is_array())
        for (const json& e : *required)
            if (e.is_string() && std::find(supportedExtensions.begin(), supportedExtensions.end(),
                                           e.get<std::string>()) == supportedExtensions.end())
                throw SceneError(path, "requires extension '" + shownText(e.get<std::string>()) +
                                           "', which LPV Engine does not support");
    checkArray(path, gltf, "nodes", "node", kNode);
    checkArray(path, gltf, "materials", "material", kMaterial);
    checkArray(path, gltf, "cameras", "camera", kCamera);
    checkArray(path, gltf, "scenes", "scene", kScene);
    checkArray(path, gltf, "accessors", "accessor", kAccessor);
    checkArray(path, gltf, "bufferViews", "bufferView", kBufferView);
    checkArray(path, gltf, "textures", "texture", kTexture);
    checkArray(path, gltf, "meshes", "mesh", {}, [&](const json& mesh, const std::string& who) {
        // tinygltf reads anything but an array as no primitives: "has no meshes to draw" said nothing.
        if (const auto p = mesh.find("primitives"); p != mesh.end() && !p->is_array())
            throw SceneError(path, who + ": primitives must be an array (of primitive objects), not " +
                                       withArticle(p->type_name()));
        checkArray(path, mesh, "primitives", (who + " primitive").c_str(), kPrimitive);
    });
    if (const auto scene = gltf.find("scene"); scene != gltf.end() && !isIndex(*scene))
        throw SceneError(path, "scene is " + shown(*scene) + ", expected " +
                                   expected({"scene", Kind::Index}, *scene));
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
