// Validation of a parsed glTF model before the reader follows its indices (see GltfValidation.h).
// Sizes come from the file as 64-bit numbers, so ranges are compared by subtraction and division:
// a product or sum of them can wrap around and pass a check it should fail.
#include "GltfValidation.h"

#include "engine/config/ShownText.h"
#include "engine/scene/SceneLoading.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

namespace lpv::engine {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Exporters write angles as 32-bit floats, and pi/2 rounded to one is a little above pi/2.
constexpr double kAngleSlack = 1e-6;

std::string quoted(const std::string& name) {
    return name.empty() ? "" : " '" + shownText(name) + "'";
}

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string numbers(const std::vector<double>& values) {
    std::string s = "(";
    for (size_t i = 0; i < values.size(); ++i)
        s += (i ? ", " : "") + number(values[i]);
    return s + ")";
}

// "major.minor", as the spec writes versions; false when the text is not of that form.
bool parseVersion(const std::string& text, int& major, int& minor) {
    const char* end = text.data() + text.size();
    const auto [dot, majorError] = std::from_chars(text.data(), end, major);
    if (majorError != std::errc() || dot == end || *dot != '.') return false;
    const auto [rest, minorError] = std::from_chars(dot + 1, end, minor);
    return minorError == std::errc() && rest == end;
}

class GltfValidator {
public:
    GltfValidator(const std::string& path, const tinygltf::Model& model) : path_(path), model_(model) {}

    void validate() const {
        checkVersion();
        checkBufferViews();
        checkAccessors();
        checkTextures();
        checkMaterials();
        checkMeshes();
        checkCameras();
        checkLights();
        checkNodes();
        checkScenes(checkHierarchy());
    }

private:
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(path_, problem); }

    // `index` must name one of `count` elements of the kind `what`.
    void requireElement(const std::string& who, int index, size_t count, const char* what) const {
        if (index < 0 || size_t(index) >= count)
            fail(who + " refers to " + what + " " + std::to_string(index) + ", which does not exist");
    }
    // As requireElement, where -1 (tinygltf's "not given") means none.
    void allowElement(const std::string& who, int index, size_t count, const char* what) const {
        if (index != -1) requireElement(who, index, count, what);
    }

    // Each of `values`, a `what` of `who`, must lie in [0, 1].
    void requireUnitRange(const std::string& who, const char* what, const std::vector<double>& values) const {
        for (double v : values)
            if (!(v >= 0.0 && v <= 1.0))
                fail(who + what + " " + (values.size() == 1 ? number(v) : numbers(values)) +
                     " must be in [0, 1]");
    }

    std::string nodeName(size_t i) const {
        return "node " + std::to_string(i) + quoted(model_.nodes[i].name);
    }

    void checkVersion() const;
    void checkBufferViews() const;
    void checkAccessors() const;
    void checkSparse(size_t accessor, size_t elementSize) const;
    void checkTextures() const;
    void checkMaterials() const;
    void checkMeshes() const;
    void checkCameras() const;
    void checkLights() const;
    void checkNodes() const;
    void checkTransform(size_t node) const;
    std::vector<int> checkHierarchy() const;
    void checkScenes(const std::vector<int>& parents) const;

    std::string path_;
    const tinygltf::Model& model_;
};

void GltfValidator::checkVersion() const {
    const tinygltf::Asset& asset = model_.asset;
    int major = 0, minor = 0;
    if (!parseVersion(asset.version, major, minor) || major != 2)
        fail("asset version '" + shownText(asset.version) + "' is not supported (glTF 2.x only)");
    // minVersion names features a reader must have: those of 2.0 are all this one knows.
    int minMajor = 0, minMinor = 0;
    if (!asset.minVersion.empty() &&
        (!parseVersion(asset.minVersion, minMajor, minMinor) || minMajor != 2 || minMinor != 0))
        fail("asset minVersion '" + shownText(asset.minVersion) + "' is not supported (glTF 2.0 only)");
}

void GltfValidator::checkBufferViews() const {
    for (size_t i = 0; i < model_.bufferViews.size(); ++i) {
        const tinygltf::BufferView& v = model_.bufferViews[i];
        const std::string who = "bufferView " + std::to_string(i);
        requireElement(who, v.buffer, model_.buffers.size(), "buffer");
        if (const std::string problem = bufferViewRangeProblem(model_, i); !problem.empty()) fail(problem);
    }
}

void GltfValidator::checkAccessors() const {
    for (size_t i = 0; i < model_.accessors.size(); ++i) {
        const tinygltf::Accessor& a = model_.accessors[i];
        const std::string who = "accessor " + std::to_string(i);
        // No bufferView (all zeros, or sparse values only) is for the reader to refuse where it is used.
        allowElement(who, a.bufferView, model_.bufferViews.size(), "bufferView");
        const int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
        const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
        if (componentSize <= 0 || components <= 0)
            fail(who + " has an invalid componentType " + std::to_string(a.componentType) + " or type");
        // The reader would bind a reference to element 0 of nothing.
        if (a.count == 0) fail(who + ": count is 0; glTF requires at least 1");
        const size_t elementSize = size_t(componentSize) * size_t(components);
        if (a.sparse.isSparse) checkSparse(i, elementSize);
        if (a.bufferView < 0) continue;
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        const size_t stride = view.byteStride ? view.byteStride : elementSize;
        // The spec's rule, byteOffset + stride * (count - 1) + elementSize <= byteLength, by division.
        const bool fits = a.byteOffset <= view.byteLength && elementSize <= view.byteLength - a.byteOffset &&
                          a.count - 1 <= (view.byteLength - a.byteOffset - elementSize) / stride;
        if (!fits)
            fail(who + ": " + std::to_string(a.count) + " elements of " + std::to_string(elementSize) +
                 " bytes, " + std::to_string(stride) + " bytes apart from byte " +
                 std::to_string(a.byteOffset) + ", do not fit in bufferView " + std::to_string(a.bufferView) +
                 " (" + std::to_string(view.byteLength) + " bytes)");
    }
}

// A sparse accessor's indices and values must lie in their bufferViews (tinygltf reads the numbers as
// ints, unchecked); that each index is in range and above the one before is the reader's to check as
// it applies them.
void GltfValidator::checkSparse(size_t i, size_t elementSize) const {
    const tinygltf::Accessor& a = model_.accessors[i];
    const std::string who = "accessor " + std::to_string(i) + ": sparse";
    const auto& sparse = a.sparse;
    if (sparse.count < 1 || size_t(sparse.count) > a.count)
        fail(who + ".count " + std::to_string(sparse.count) + " must be in [1, " + std::to_string(a.count) +
             "] (the accessor's count)");
    const int indexType = sparse.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(who + ".indices.componentType " + std::to_string(indexType) +
             " is not an unsigned byte (5121), short (5123) or int (5125)");
    const size_t indexSize = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(indexType)));
    const std::pair<const char*, std::pair<int, int>> parts[] = {
        {".indices", {sparse.indices.bufferView, sparse.indices.byteOffset}},
        {".values", {sparse.values.bufferView, sparse.values.byteOffset}}};
    for (const auto& [part, where] : parts) {
        const auto [viewIndex, offset] = where;
        requireElement(who + part, viewIndex, model_.bufferViews.size(), "bufferView");
        const size_t size = part[1] == 'i' ? indexSize : elementSize;
        const tinygltf::BufferView& view = model_.bufferViews[size_t(viewIndex)];
        // count * size + offset <= byteLength, by division.
        if (offset < 0 || size_t(offset) > view.byteLength ||
            size_t(sparse.count) > (view.byteLength - size_t(offset)) / size)
            fail(who + part + ": " + std::to_string(sparse.count) + " elements of " + std::to_string(size) +
                 " bytes from byte " + std::to_string(offset) + " do not fit in bufferView " +
                 std::to_string(viewIndex) + " (" + std::to_string(view.byteLength) + " bytes)");
    }
}

void GltfValidator::checkTextures() const {
    for (size_t i = 0; i < model_.textures.size(); ++i) {
        const tinygltf::Texture& t = model_.textures[i];
        const std::string who = "texture " + std::to_string(i);
        // No source is allowed (an extension may give it); the reader warns and uses the flat factor.
        allowElement(who, t.source, model_.images.size(), "image");
        allowElement(who, t.sampler, model_.samplers.size(), "sampler");
    }
}

void GltfValidator::checkMaterials() const {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& m = model_.materials[i];
        const std::string who = "material " + std::to_string(i) + quoted(m.name) + ": ";
        const size_t textures = model_.textures.size();
        allowElement(who + "baseColorTexture", m.pbrMetallicRoughness.baseColorTexture.index, textures,
                     "texture");
        allowElement(who + "metallicRoughnessTexture", m.pbrMetallicRoughness.metallicRoughnessTexture.index,
                     textures, "texture");
        allowElement(who + "normalTexture", m.normalTexture.index, textures, "texture");
        allowElement(who + "occlusionTexture", m.occlusionTexture.index, textures, "texture");
        allowElement(who + "emissiveTexture", m.emissiveTexture.index, textures, "texture");
        requireUnitRange(who, "baseColorFactor", m.pbrMetallicRoughness.baseColorFactor);
        requireUnitRange(who, "metallicFactor", {m.pbrMetallicRoughness.metallicFactor});
        requireUnitRange(who, "roughnessFactor", {m.pbrMetallicRoughness.roughnessFactor});
        if (m.emissiveFactor.size() != 3)
            fail(who + "emissiveFactor has " + std::to_string(m.emissiveFactor.size()) +
                 " numbers, expected 3");
        requireUnitRange(who, "emissiveFactor", m.emissiveFactor);
        if (auto it = m.extensions.find("KHR_materials_emissive_strength");
            it != m.extensions.end() && it->second.Has("emissiveStrength")) {
            const tinygltf::Value& strength = it->second.Get("emissiveStrength");
            if (!strength.IsNumber() || !(strength.GetNumberAsDouble() >= 0.0) ||
                !std::isfinite(strength.GetNumberAsDouble()))
                fail(who + "KHR_materials_emissive_strength emissiveStrength must be a number, 0 or more");
        }
    }
}

void GltfValidator::checkMeshes() const {
    for (size_t mi = 0; mi < model_.meshes.size(); ++mi) {
        const tinygltf::Mesh& mesh = model_.meshes[mi];
        for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const tinygltf::Primitive& prim = mesh.primitives[pi];
            const std::string where =
                "mesh " + std::to_string(mi) + quoted(mesh.name) + " primitive " + std::to_string(pi);
            for (const auto& [name, accessor] : prim.attributes)
                requireElement(where + ": attribute " + name, accessor, model_.accessors.size(), "accessor");
            allowElement(where + ": \"indices\"", prim.indices, model_.accessors.size(), "accessor");
            allowElement(where, prim.material, model_.materials.size(), "material");
        }
    }
}

void GltfValidator::checkCameras() const {
    for (size_t i = 0; i < model_.cameras.size(); ++i) {
        const tinygltf::Camera& c = model_.cameras[i];
        const std::string who = "camera " + std::to_string(i) + quoted(c.name) + ": ";
        // tinygltf reads a zfar or aspectRatio that is not given as 0.
        if (c.type == "perspective") {
            const tinygltf::PerspectiveCamera& p = c.perspective;
            if (!(p.yfov > 0.0 && p.yfov < kPi)) fail(who + "yfov " + number(p.yfov) + " must be in (0, pi)");
            if (!(p.znear > 0.0) || !std::isfinite(p.znear))
                fail(who + "znear " + number(p.znear) + " must be greater than 0");
            if (p.zfar != 0.0 && !(p.zfar > p.znear))
                fail(who + "zfar " + number(p.zfar) + " must be greater than znear " + number(p.znear));
            if (p.aspectRatio != 0.0 && !(p.aspectRatio > 0.0))
                fail(who + "aspectRatio " + number(p.aspectRatio) + " must be greater than 0");
        } else {
            const tinygltf::OrthographicCamera& o = c.orthographic;
            if (o.xmag == 0.0 || o.ymag == 0.0) fail(who + "xmag and ymag must not be 0");
            if (!(o.znear >= 0.0)) fail(who + "znear " + number(o.znear) + " must be 0 or more");
            if (!(o.zfar > o.znear))
                fail(who + "zfar " + number(o.zfar) + " must be greater than znear " + number(o.znear));
        }
    }
}

void GltfValidator::checkLights() const {
    for (size_t i = 0; i < model_.lights.size(); ++i) {
        const tinygltf::Light& l = model_.lights[i];
        const std::string who = "light " + std::to_string(i) + quoted(l.name) + ": ";
        if (l.type != "directional" && l.type != "spot" && l.type != "point")
            fail(who + "type '" + shownText(l.type) + "' is not directional, point or spot");
        if (!l.color.empty() && l.color.size() != 3)
            fail(who + "color has " + std::to_string(l.color.size()) + " numbers, expected 3");
        requireUnitRange(who, "color", l.color);
        if (!(l.intensity >= 0.0) || !std::isfinite(l.intensity))
            fail(who + "intensity " + number(l.intensity) + " must be 0 or more");
        // The renderer holds it as a float: beyond that it would be infinite, and the lit pixels NaN.
        if (l.intensity > double(std::numeric_limits<float>::max()))
            fail(who + "intensity " + number(l.intensity) + " is too large (at most " +
                 number(double(std::numeric_limits<float>::max())) + ")");
        // tinygltf reads a range that is not given (no limit) as 0.
        if (l.range != 0.0 && (!(l.range > 0.0) || !std::isfinite(l.range)))
            fail(who + "range " + number(l.range) + " must be greater than 0");
        if (l.type != "spot") continue;
        const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
        if (!(outer > 0.0 && outer <= kPi / 2.0 + kAngleSlack))
            fail(who + "outerConeAngle " + number(outer) + " must be in (0, pi/2]");
        if (!(inner >= 0.0 && inner < outer))
            fail(who + "innerConeAngle " + number(inner) + " must be in [0, outerConeAngle " + number(outer) +
                 ")");
    }
}

void GltfValidator::checkTransform(size_t i) const {
    const tinygltf::Node& n = model_.nodes[i];
    const std::string who = nodeName(i) + ": ";
    const std::pair<const char*, const std::vector<double>*> parts[] = {{"matrix", &n.matrix},
                                                                        {"translation", &n.translation},
                                                                        {"rotation", &n.rotation},
                                                                        {"scale", &n.scale}};
    const size_t sizes[] = {16, 3, 4, 3};
    for (size_t p = 0; p < 4; ++p) {
        const auto& [what, values] = parts[p];
        if (!values->empty() && values->size() != sizes[p])
            fail(who + what + " has " + std::to_string(values->size()) + " numbers, expected " +
                 std::to_string(sizes[p]));
        for (double v : *values)
            if (!std::isfinite(v)) fail(who + what + " has a value that is not finite");
    }
    if (n.rotation.size() == 4) {
        double lengthSquared = 0.0;
        for (double v : n.rotation)
            lengthSquared += v * v;
        // Loose enough for quaternions written to a few decimals; a zero one would become no rotation.
        if (std::abs(std::sqrt(lengthSquared) - 1.0) > 0.01)
            fail(who + "rotation " + numbers(n.rotation) + " is not a unit quaternion");
    }
}

void GltfValidator::checkNodes() const {
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
        const tinygltf::Node& n = model_.nodes[i];
        const std::string who = nodeName(i);
        allowElement(who, n.mesh, model_.meshes.size(), "mesh");
        allowElement(who, n.camera, model_.cameras.size(), "camera");
        checkTransform(i);
        for (int child : n.children)
            requireElement(who + ": child", child, model_.nodes.size(), "node");
        if (auto it = n.extensions.find("KHR_lights_punctual");
            it != n.extensions.end() && it->second.Has("light")) {
            const tinygltf::Value& light = it->second.Get("light");
            if (!light.IsInt()) fail(who + ": KHR_lights_punctual \"light\" is not an integer index");
            requireElement(who, light.GetNumberAsInt(), model_.lights.size(), "light");
        }
    }
}

// glTF nodes form disjoint strict trees: one parent at most, and no node its own ancestor (the
// reader would go round a loop for ever). Returns each node's parent, -1 for none.
std::vector<int> GltfValidator::checkHierarchy() const {
    std::vector<int> parents(model_.nodes.size(), -1);
    for (size_t p = 0; p < model_.nodes.size(); ++p)
        for (int child : model_.nodes[p].children) {
            int& parent = parents[size_t(child)];
            if (parent == int(p))
                fail(nodeName(p) + " lists node " + std::to_string(child) + " twice among its children");
            if (parent != -1)
                fail(nodeName(size_t(child)) + " has two parents, nodes " + std::to_string(parent) + " and " +
                     std::to_string(p));
            parent = int(p);
        }
    // Walk up from each node in turn; meeting a node of the same walk again is a loop.
    std::vector<int> walk(model_.nodes.size(), -1);
    for (size_t start = 0; start < model_.nodes.size(); ++start) {
        int node = int(start);
        while (node != -1 && walk[size_t(node)] == -1) {
            walk[size_t(node)] = int(start);
            node = parents[size_t(node)];
        }
        if (node != -1 && walk[size_t(node)] == int(start))
            fail(nodeName(size_t(node)) + " is its own ancestor");
    }
    return parents;
}

void GltfValidator::checkScenes(const std::vector<int>& parents) const {
    for (size_t s = 0; s < model_.scenes.size(); ++s) {
        const std::string who = "scene " + std::to_string(s);
        std::set<int> roots;
        for (int root : model_.scenes[s].nodes) {
            requireElement(who, root, model_.nodes.size(), "node");
            if (!roots.insert(root).second) fail(who + " lists node " + std::to_string(root) + " twice");
            if (const int parent = parents[size_t(root)]; parent != -1)
                fail(who + " lists node " + std::to_string(root) + " as a root, but it is a child of node " +
                     std::to_string(parent));
        }
    }
    allowElement("\"scene\"", model_.defaultScene, model_.scenes.size(), "scene");
}

} // namespace

std::string bufferViewRangeProblem(const tinygltf::Model& model, size_t view) {
    const tinygltf::BufferView& v = model.bufferViews[view];
    const size_t size = model.buffers[size_t(v.buffer)].data.size();
    if (v.byteOffset <= size && v.byteLength <= size - v.byteOffset) return "";
    return "bufferView " + std::to_string(view) + " (" + std::to_string(v.byteLength) + " bytes from byte " +
           std::to_string(v.byteOffset) + ") runs past the end of buffer " + std::to_string(v.buffer) + " (" +
           std::to_string(size) + " bytes)";
}

void validateGltf(const std::string& path, const tinygltf::Model& model) {
    GltfValidator(path, model).validate();
}

} // namespace lpv::engine
