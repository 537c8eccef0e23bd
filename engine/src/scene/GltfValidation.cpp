// Validation of a parsed glTF model before the reader follows its indices (see GltfValidation.h).
// Sizes come from the file as 64-bit numbers, so ranges are compared by subtraction and division:
// a product or sum of them can wrap around and pass a check it should fail.
#include "GltfValidation.h"

#include "engine/scene/SceneLoading.h"

#include <set>
#include <vector>

namespace lpv::engine {
namespace {

std::string quoted(const std::string& name) {
    return name.empty() ? "" : " '" + name + "'";
}

class GltfValidator {
public:
    GltfValidator(const std::string& path, const tinygltf::Model& model) : path_(path), model_(model) {}

    void validate() const {
        checkBufferViews();
        checkAccessors();
        checkTextures();
        checkMaterials();
        checkMeshes();
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

    std::string nodeName(size_t i) const {
        return "node " + std::to_string(i) + quoted(model_.nodes[i].name);
    }

    void checkBufferViews() const;
    void checkAccessors() const;
    void checkTextures() const;
    void checkMaterials() const;
    void checkMeshes() const;
    void checkNodes() const;
    std::vector<int> checkHierarchy() const;
    void checkScenes(const std::vector<int>& parents) const;

    std::string path_;
    const tinygltf::Model& model_;
};

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
        if (a.bufferView < 0 || a.count == 0) continue;
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        const size_t elementSize = size_t(componentSize) * size_t(components);
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

void GltfValidator::checkNodes() const {
    for (size_t i = 0; i < model_.nodes.size(); ++i) {
        const tinygltf::Node& n = model_.nodes[i];
        const std::string who = nodeName(i);
        allowElement(who, n.mesh, model_.meshes.size(), "mesh");
        allowElement(who, n.camera, model_.cameras.size(), "camera");
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
