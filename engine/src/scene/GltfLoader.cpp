// glTF 2.0 through tinygltf, validated on the way in: the file's references and accessor ranges
// (GltfValidation.cpp), then index ranges and finite positions here, because tinygltf checks none of
// them, and a bad file must be an error, not a crash or a garbage frame.
#include "GltfJsonTypes.h"
#include "GltfValidation.h"

#include "engine/config/ShownText.h"
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/SceneLoading.h"

#include "platforms/Log.h"

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <utility>

namespace lpv::engine {
namespace {

const char* const kSupportedExtensions[] = {"KHR_lights_punctual", "KHR_materials_emissive_strength"};

// tinygltf's message on one line, and a data URI it quotes (megabytes of base64) cut short.
std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' '))
        s.pop_back();
    for (char& c : s)
        if (c == '\n') c = ';';
    constexpr size_t kShown = 48;
    for (size_t at = s.find("data:"); at != std::string::npos; at = s.find("data:", at + 1)) {
        size_t end = at;
        while (end < s.size() && s[end] != ' ' && s[end] != '\'' && s[end] != '"' && s[end] != ';')
            ++end;
        // The media type ends at the first ';' ("data:application/octet-stream;base64,...").
        if (end < s.size() && s[end] == ';' && s.compare(end, 8, ";base64,") == 0) {
            end += 8;
            while (end < s.size() && s[end] != ' ' && s[end] != '\'' && s[end] != '"' && s[end] != ';')
                ++end;
        }
        if (end - at > kShown)
            s.replace(at + kShown, end - at - kShown, "... (" + std::to_string(end - at) + " characters)");
    }
    return s;
}

// The triangles of a strip or a fan as a list, in the order and winding glTF 2.0 gives (3.7.2.1):
// strip triangle i is (v[i], v[i+1], v[i+2]) for even i and (v[i], v[i+2], v[i+1]) for odd i, so that
// every triangle faces the way the first does; fan triangle i is (v[i+1], v[i+2], v[0]).
std::vector<uint32_t> triangleList(const std::vector<uint32_t>& v, bool strip) {
    std::vector<uint32_t> list;
    list.reserve((v.size() - 2) * 3);
    for (size_t i = 0; i + 2 < v.size(); ++i) {
        if (!strip)
            list.insert(list.end(), {v[i + 1], v[i + 2], v[0]});
        else if (i % 2 == 0)
            list.insert(list.end(), {v[i], v[i + 1], v[i + 2]});
        else
            list.insert(list.end(), {v[i], v[i + 2], v[i + 1]});
    }
    return list;
}

class GltfReader {
public:
    GltfReader(const std::string& path, const tinygltf::Model& model) : path_(path), model_(model) {}

    Scene read();

private:
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(path_, problem); }

    // A camera or light points along its node's -z: a world transform that collapses a dimension
    // (a zero scale) leaves that undefined, and normalize() would make it NaN.
    glm::vec3 direction(const glm::mat4& world, glm::vec3 axis, int node, const std::string& what) const;

    // An accessor's elements, `stride` bytes apart from `data`: in its bufferView (validateGltf has
    // checked the range), or in `copy` when it is sparse or has no bufferView.
    struct Elements {
        const uint8_t* data = nullptr;
        size_t stride = 0;
        size_t count = 0;
        std::vector<uint8_t> copy;
    };
    Elements accessorData(int accessorIndex, size_t elementSize) const;
    // `integers`: also normalized unsigned bytes and shorts, as glTF 2.0 allows for texture
    // coordinates (positions, normals and tangents are floats unless KHR_mesh_quantization, which
    // this reader does not support, is required).
    template <int N>
    std::vector<glm::vec<N, float>> readFloats(int accessorIndex, const char* what,
                                               bool integers = false) const;
    std::vector<uint32_t> readIndices(int accessorIndex) const;
    // `material`: how warnings name the material that uses it ("material 2 'brick'").
    int32_t texture(int gltfTexture, bool srgb, const std::string& material);
    void readMaterials();
    void readMeshes();
    void visitTree(int root);
    glm::mat4 visit(int node, const glm::mat4& parent);

    std::string path_;
    const tinygltf::Model& model_;
    Scene scene_;
    std::map<std::pair<int, bool>, int32_t> textures_;   // (glTF texture, sRGB) -> scene texture
    std::vector<std::vector<uint32_t>> primitiveMeshes_; // glTF mesh -> engine meshes
    size_t skippedPrimitives_ = 0;                       // points and lines
};

// Elements an accessor without a bufferView may have: it is built in memory, all zeros but for its
// sparse values, and a count from the file must not size that unchecked (16 bytes each: 1 GiB).
constexpr size_t kMaxBuiltElements = size_t(1) << 26;

GltfReader::Elements GltfReader::accessorData(int accessorIndex, size_t elementSize) const {
    const tinygltf::Accessor& a = model_.accessors[size_t(accessorIndex)];
    const std::string who = "accessor " + std::to_string(accessorIndex);
    Elements e;
    e.count = a.count;
    if (a.bufferView >= 0) {
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        e.stride = view.byteStride ? view.byteStride : elementSize;
        e.data = model_.buffers[size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
        if (!a.sparse.isSparse) return e;
    }
    // glTF 2.0: the base elements (zeros without a bufferView), then each sparse value at its index.
    if (a.count > kMaxBuiltElements)
        fail(who + ": " + std::to_string(a.count) +
             " elements without a bufferView or sparse are more than the " +
             std::to_string(kMaxBuiltElements) + " the engine builds");
    e.copy.assign(a.count * elementSize, 0);
    if (e.data)
        for (size_t i = 0; i < a.count; ++i)
            std::memcpy(e.copy.data() + i * elementSize, e.data + i * e.stride, elementSize);
    if (a.sparse.isSparse) {
        // validateGltf has checked that both ranges lie in their bufferViews.
        const auto viewData = [&](int view, int offset) {
            const tinygltf::BufferView& v = model_.bufferViews[size_t(view)];
            return model_.buffers[size_t(v.buffer)].data.data() + v.byteOffset + size_t(offset);
        };
        const uint8_t* indices = viewData(a.sparse.indices.bufferView, a.sparse.indices.byteOffset);
        const uint8_t* values = viewData(a.sparse.values.bufferView, a.sparse.values.byteOffset);
        const int indexSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.sparse.indices.componentType));
        size_t previous = 0;
        for (size_t k = 0; k < size_t(a.sparse.count); ++k) {
            uint32_t index = 0;
            if (indexSize == 1)
                index = indices[k];
            else if (indexSize == 2) {
                uint16_t u;
                std::memcpy(&u, indices + k * 2, 2);
                index = u;
            } else
                std::memcpy(&index, indices + k * 4, 4);
            if (index >= a.count || (k > 0 && index <= previous))
                fail(who + ": sparse index " + std::to_string(index) + " (number " + std::to_string(k) +
                     ") " +
                     (index >= a.count ? "is out of range (" + std::to_string(a.count) + " elements)"
                                       : "is not greater than the one before it"));
            previous = index;
            std::memcpy(e.copy.data() + size_t(index) * elementSize, values + k * elementSize, elementSize);
        }
    }
    e.data = e.copy.data();
    e.stride = elementSize;
    return e;
}

template <int N>
std::vector<glm::vec<N, float>> GltfReader::readFloats(int accessorIndex, const char* what,
                                                       bool integers) const {
    const tinygltf::Accessor& a = model_.accessors[size_t(accessorIndex)];
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        const bool normalizedInteger = (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                        a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) &&
                                       a.normalized;
        if (!integers || !normalizedInteger)
            fail(std::string(what) + " accessor " + std::to_string(accessorIndex) + " has component type " +
                 std::to_string(a.componentType) + (a.normalized ? " (normalized)" : "") + ", expected " +
                 (integers ? "float (5126), or normalized unsigned byte (5121) or short (5123)"
                           : "float (5126)"));
    }
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (components != N)
        fail(std::string(what) + " accessor " + std::to_string(accessorIndex) + " has " +
             std::to_string(components) + " components, expected " + std::to_string(N));
    const int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (componentSize <= 0) fail(std::string(what) + " accessor has an invalid component type");
    const Elements elements = accessorData(accessorIndex, size_t(componentSize) * N);
    std::vector<glm::vec<N, float>> out(elements.count);
    for (size_t i = 0; i < elements.count; ++i) {
        const uint8_t* e = elements.data + i * elements.stride;
        for (int c = 0; c < N; ++c) {
            float v = 0.0f;
            switch (a.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT:
                std::memcpy(&v, e + c * 4, 4);
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                v = float(e[c]) / 255.0f;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t u;
                std::memcpy(&u, e + c * 2, 2);
                v = float(u) / 65535.0f;
                break;
            }
            default:
                fail(std::string(what) + " accessor " + std::to_string(accessorIndex) +
                     " has an unsupported component type " + std::to_string(a.componentType));
            }
            out[i][c] = v;
        }
    }
    return out;
}

std::vector<uint32_t> GltfReader::readIndices(int accessorIndex) const {
    const tinygltf::Accessor& a = model_.accessors[size_t(accessorIndex)];
    const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    if (a.type != TINYGLTF_TYPE_SCALAR || (size != 1 && size != 2 && size != 4) ||
        a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail("index accessor " + std::to_string(accessorIndex) + " is not an unsigned integer scalar");
    const Elements elements = accessorData(accessorIndex, size_t(size));
    std::vector<uint32_t> out(elements.count);
    for (size_t i = 0; i < elements.count; ++i) {
        const uint8_t* e = elements.data + i * elements.stride;
        if (size == 1)
            out[i] = e[0];
        else if (size == 2) {
            uint16_t u;
            std::memcpy(&u, e, 2);
            out[i] = u;
        } else
            std::memcpy(&out[i], e, 4);
    }
    return out;
}

int32_t GltfReader::texture(int gltfTexture, bool srgb, const std::string& material) {
    if (gltfTexture < 0) return -1;
    const auto key = std::make_pair(gltfTexture, srgb);
    if (auto it = textures_.find(key); it != textures_.end()) return it->second;
    int32_t result = -1;
    const int source = model_.textures[size_t(gltfTexture)].source;
    const tinygltf::Image* image = source >= 0 ? &model_.images[size_t(source)] : nullptr;
    if (!image || image->image.empty() || image->width <= 0 || image->height <= 0 ||
        image->image.size() < size_t(image->width) * size_t(image->height) * size_t(image->component)) {
        log::warn(path_ + ": texture " + std::to_string(gltfTexture) + " (" +
                  (image ? shownText(image->uri) : "no image") + ") could not be loaded; " + material +
                  " uses its flat factor instead");
    } else if (image->bits != 8 || (image->component != 3 && image->component != 4)) {
        log::warn(path_ + ": texture " + std::to_string(gltfTexture) + " has " +
                  std::to_string(image->component) + " components of " + std::to_string(image->bits) +
                  " bits; only 8-bit RGB(A) is used, " + material + " uses its flat factor instead");
    } else {
        TextureImage t;
        t.name = image->name.empty() ? image->uri : image->name;
        t.width = uint32_t(image->width);
        t.height = uint32_t(image->height);
        t.srgb = srgb;
        t.rgba.resize(size_t(t.width) * t.height * 4);
        const size_t pixels = size_t(t.width) * t.height;
        for (size_t p = 0; p < pixels; ++p)
            for (int c = 0; c < 4; ++c)
                t.rgba[p * 4 + size_t(c)] =
                    c < image->component ? image->image[p * size_t(image->component) + size_t(c)] : 255;
        result = int32_t(scene_.textures.size());
        scene_.textures.push_back(std::move(t));
    }
    textures_[key] = result;
    return result;
}

void GltfReader::readMaterials() {
    for (size_t mi = 0; mi < model_.materials.size(); ++mi) {
        const tinygltf::Material& m = model_.materials[mi];
        // Named by index, and by name where it has one (many exporters leave it empty).
        const std::string material =
            "material " + std::to_string(mi) + (m.name.empty() ? "" : " '" + shownText(m.name) + "'");
        Material out;
        out.name = m.name;
        const auto& pbr = m.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4)
            out.baseColor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                                      pbr.baseColorFactor[3]);
        out.metallic = float(pbr.metallicFactor);
        out.roughness = float(pbr.roughnessFactor);
        out.baseColorTexture = texture(pbr.baseColorTexture.index, true, material);
        out.metallicRoughnessTexture = texture(pbr.metallicRoughnessTexture.index, false, material);
        out.normalTexture = texture(m.normalTexture.index, false, material);
        out.emissiveTexture = texture(m.emissiveTexture.index, true, material);
        // What the renderer does otherwise is said, not dropped unnoticed. SSAO darkens the indirect
        // light instead of an occlusion map; every surface is drawn opaque; every map is read
        // through the first set of texture coordinates, the only one the vertices keep.
        const std::string who = path_ + ": " + material + ": ";
        if (m.occlusionTexture.index >= 0)
            log::warn(who + "occlusionTexture is not used (screen-space ambient occlusion stands in for it)");
        if (!m.alphaMode.empty() && m.alphaMode != "OPAQUE")
            log::warn(who + "alphaMode " + shownText(m.alphaMode) + " is drawn as OPAQUE");
        const std::pair<const char*, int> sets[] = {
            {"baseColorTexture", pbr.baseColorTexture.texCoord},
            {"metallicRoughnessTexture", pbr.metallicRoughnessTexture.texCoord},
            {"normalTexture", m.normalTexture.texCoord},
            {"emissiveTexture", m.emissiveTexture.texCoord}};
        for (const auto& [map, set] : sets)
            if (set != 0)
                log::warn(who + map + " names TEXCOORD_" + std::to_string(set) +
                          "; it is read through TEXCOORD_0");
        if (m.emissiveFactor.size() == 3)
            out.emissive = glm::vec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]);
        if (auto it = m.extensions.find("KHR_materials_emissive_strength");
            it != m.extensions.end() && it->second.Has("emissiveStrength"))
            out.emissive *= float(it->second.Get("emissiveStrength").GetNumberAsDouble());
        scene_.materials.push_back(out);
    }
    if (scene_.materials.empty()) scene_.materials.push_back({"default", glm::vec4(0.8f, 0.8f, 0.8f, 1.0f)});
}

void GltfReader::readMeshes() {
    for (size_t mi = 0; mi < model_.meshes.size(); ++mi) {
        const tinygltf::Mesh& mesh = model_.meshes[mi];
        std::vector<uint32_t> engineMeshes;
        for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
            const tinygltf::Primitive& prim = mesh.primitives[pi];
            const std::string where = "mesh " + std::to_string(mi) + " '" + shownText(mesh.name) +
                                      "' primitive " + std::to_string(pi);
            // The renderer and the GI draw triangles: strips and fans become lists below; points and
            // lines are skipped, and read() says how many, once.
            const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
                mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
                ++skippedPrimitives_;
                continue;
            }
            if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                mode != TINYGLTF_MODE_TRIANGLE_FAN)
                fail(where + ": primitive mode " + std::to_string(mode) + " is not a glTF mode (0 to 6)");
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) fail(where + ": has no POSITION attribute");
            const auto positions = readFloats<3>(pos->second, "POSITION");
            for (size_t v = 0; v < positions.size(); ++v)
                if (!std::isfinite(positions[v].x) || !std::isfinite(positions[v].y) ||
                    !std::isfinite(positions[v].z))
                    fail(where + ": vertex " + std::to_string(v) +
                         " has a non-finite position (NaN or infinity)");
            std::vector<glm::vec3> normals;
            std::vector<glm::vec2> uvs;
            std::vector<glm::vec4> tangents;
            if (auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end())
                normals = readFloats<3>(it->second, "NORMAL");
            if (auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end())
                uvs = readFloats<2>(it->second, "TEXCOORD_0", true);
            if (auto it = prim.attributes.find("TANGENT"); it != prim.attributes.end())
                tangents = readFloats<4>(it->second, "TANGENT");
            for (const auto* attr : {&normals})
                if (!attr->empty() && attr->size() != positions.size())
                    fail(where + ": NORMAL count differs from POSITION count");
            if (!uvs.empty() && uvs.size() != positions.size())
                fail(where + ": TEXCOORD_0 count differs from POSITION count");
            if (!tangents.empty() && tangents.size() != positions.size())
                fail(where + ": TANGENT count differs from POSITION count");
            if (uvs.empty() && prim.material >= 0) {
                const tinygltf::Material& m = model_.materials[size_t(prim.material)];
                if (m.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
                    m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 ||
                    m.normalTexture.index >= 0 || m.emissiveTexture.index >= 0)
                    log::warn(
                        path_ + ": " + where + ": material " + std::to_string(prim.material) +
                        (m.name.empty() ? "" : " '" + shownText(m.name) + "'") +
                        " has texture maps but the primitive has no TEXCOORD_0; each map is read at its "
                        "first texel");
            }

            std::vector<uint32_t> indices;
            if (prim.indices >= 0)
                indices = readIndices(prim.indices);
            else
                for (uint32_t i = 0; i < positions.size(); ++i)
                    indices.push_back(i);
            for (size_t i = 0; i < indices.size(); ++i)
                if (indices[i] >= positions.size())
                    fail(where + ": index " + std::to_string(indices[i]) + " at position " +
                         std::to_string(i) + " is out of range (" + std::to_string(positions.size()) +
                         " vertices)");
            if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3)
                fail(where + ": index count " + std::to_string(indices.size()) + " is not a multiple of 3");
            if (mode != TINYGLTF_MODE_TRIANGLES) {
                const char* name = mode == TINYGLTF_MODE_TRIANGLE_STRIP ? "TRIANGLE_STRIP" : "TRIANGLE_FAN";
                if (indices.size() < 3)
                    fail(where + ": " + name + " has " + std::to_string(indices.size()) +
                         " vertices, fewer than the 3 of one triangle");
                indices = triangleList(indices, mode == TINYGLTF_MODE_TRIANGLE_STRIP);
            }

            Mesh out;
            out.name = mesh.name;
            out.material = prim.material >= 0 ? uint32_t(prim.material) : 0; // 0: the default material
            out.firstIndex = uint32_t(scene_.indices.size());
            out.indexCount = uint32_t(indices.size());
            const uint32_t base = uint32_t(scene_.vertices.size());
            for (size_t v = 0; v < positions.size(); ++v) {
                Vertex vert;
                vert.position = positions[v];
                if (!normals.empty()) vert.normal = normals[v];
                if (!uvs.empty()) vert.uv = uvs[v];
                if (!tangents.empty()) vert.tangent = tangents[v];
                out.bounds.add(vert.position);
                scene_.vertices.push_back(vert);
            }
            if (normals.empty()) {
                // Area-weighted vertex normals when the file has none.
                for (Vertex* v = &scene_.vertices[base]; v != scene_.vertices.data() + scene_.vertices.size();
                     ++v)
                    v->normal = glm::vec3(0.0f);
                for (size_t i = 0; i + 2 < indices.size(); i += 3) {
                    Vertex &a = scene_.vertices[base + indices[i]],
                           &b = scene_.vertices[base + indices[i + 1]],
                           &c = scene_.vertices[base + indices[i + 2]];
                    const glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
                    a.normal += n;
                    b.normal += n;
                    c.normal += n;
                }
                for (size_t v = base; v < scene_.vertices.size(); ++v) {
                    const float len = glm::length(scene_.vertices[v].normal);
                    scene_.vertices[v].normal =
                        len > 0.0f ? scene_.vertices[v].normal / len : glm::vec3(0, 1, 0);
                }
            }
            for (uint32_t i : indices)
                scene_.indices.push_back(base + i);
            engineMeshes.push_back(uint32_t(scene_.meshes.size()));
            scene_.meshes.push_back(out);
        }
        primitiveMeshes_.push_back(std::move(engineMeshes));
    }
}

glm::mat4 localTransform(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i)
            glm::value_ptr(m)[i] = float(n.matrix[size_t(i)]);
        return m;
    }
    glm::mat4 m(1.0f);
    if (n.translation.size() == 3)
        m = glm::translate(m, glm::vec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4)
        m *= glm::mat4_cast(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                                      float(n.rotation[2])));
    if (n.scale.size() == 3) m = glm::scale(m, glm::vec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

glm::vec3 GltfReader::direction(const glm::mat4& world, glm::vec3 axis, int node,
                                const std::string& what) const {
    const glm::vec3 d = glm::normalize(glm::vec3(world * glm::vec4(axis, 0.0f)));
    const double det = glm::determinant(glm::dmat3(glm::mat3(world)));
    if (!(std::abs(det) > 0.0) || !std::isfinite(det) || !std::isfinite(d.x) || !std::isfinite(d.y) ||
        !std::isfinite(d.z)) {
        const std::string& name = model_.nodes[size_t(node)].name;
        fail("node " + std::to_string(node) + (name.empty() ? "" : " '" + name + "'") +
             ": its world transform is singular (a zero scale), so " + what + " on it has no direction");
    }
    return d;
}

// Adds the node's meshes, camera and light; returns its world transform.
glm::mat4 GltfReader::visit(int nodeIndex, const glm::mat4& parent) {
    const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
    const glm::mat4 world = parent * localTransform(node);
    if (node.mesh >= 0) {
        for (uint32_t m : primitiveMeshes_[size_t(node.mesh)]) {
            Instance inst;
            inst.mesh = m;
            inst.transform = world;
            scene_.instances.push_back(inst);
        }
    }
    const glm::vec3 position(world[3]);
    if (node.camera >= 0) {
        const std::string what = "camera " + std::to_string(node.camera);
        const glm::vec3 forward = direction(world, {0, 0, -1}, nodeIndex, what);
        const glm::vec3 up = direction(world, {0, 1, 0}, nodeIndex, what);
        const tinygltf::Camera& c = model_.cameras[size_t(node.camera)];
        if (!scene_.camera) {
            Camera cam;
            cam.position = position;
            cam.forward = forward;
            cam.up = up;
            if (c.type == "perspective") {
                cam.verticalFov = float(c.perspective.yfov);
                cam.nearPlane = float(c.perspective.znear);
                if (c.perspective.zfar > 0) cam.farPlane = float(c.perspective.zfar);
            } else {
                log::warn(path_ + ": " + what +
                          " is orthographic; it is drawn in perspective with the default field of view");
            }
            scene_.camera = cam;
        }
    }
    if (auto it = node.extensions.find("KHR_lights_punctual");
        it != node.extensions.end() && it->second.Has("light")) {
        const int li = it->second.Get("light").GetNumberAsInt();
        const tinygltf::Light& l = model_.lights[size_t(li)];
        Light out;
        out.name = l.name;
        out.type = l.type == "directional" ? LightType::Directional
                   : l.type == "spot"      ? LightType::Spot
                                           : LightType::Point;
        if (l.color.size() == 3) out.color = glm::vec3(l.color[0], l.color[1], l.color[2]);
        out.intensity = float(l.intensity);
        out.range = float(l.range);
        out.position = position;
        out.direction = direction(world, {0, 0, -1}, nodeIndex, "light " + std::to_string(li));
        out.innerConeAngle = float(l.spot.innerConeAngle);
        out.outerConeAngle = float(l.spot.outerConeAngle);
        scene_.lights.push_back(out);
    }
    return world;
}

// Depth first in the file's order (the first camera met is the view), on a stack of its own: a legal
// hierarchy can be deeper than the call stack. validateGltf has ruled out loops.
void GltfReader::visitTree(int root) {
    std::vector<std::pair<int, glm::mat4>> pending{{root, glm::mat4(1.0f)}};
    while (!pending.empty()) {
        const auto [node, parent] = pending.back();
        pending.pop_back();
        const glm::mat4 world = visit(node, parent);
        const std::vector<int>& children = model_.nodes[size_t(node)].children;
        for (auto child = children.rbegin(); child != children.rend(); ++child)
            pending.emplace_back(*child, world);
    }
}

Scene GltfReader::read() {
    // A required extension the engine lacks was refused by checkGltfJson, before tinygltf.
    // An optional extension the reader does not know (KHR_texture_transform, KHR_materials_clearcoat...)
    // changes what the author meant to be seen: said once, not dropped unnoticed.
    for (const std::string& ext : model_.extensionsUsed)
        if (std::find(std::begin(kSupportedExtensions), std::end(kSupportedExtensions), ext) ==
            std::end(kSupportedExtensions))
            log::warn(path_ + ": uses extension '" + shownText(ext) + "', which LPV Engine ignores");
    scene_.name = std::filesystem::path(path_).stem().string();
    readMaterials();
    readMeshes();
    if (!model_.scenes.empty()) {
        const size_t s = model_.defaultScene >= 0 ? size_t(model_.defaultScene) : 0;
        for (int n : model_.scenes[s].nodes)
            visitTree(n);
    } else {
        // No scenes: every tree, each once from its root.
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const tinygltf::Node& n : model_.nodes)
            for (int child : n.children)
                isChild[size_t(child)] = true;
        for (size_t n = 0; n < model_.nodes.size(); ++n)
            if (!isChild[n]) visitTree(int(n));
    }
    const std::string skipped = std::to_string(skippedPrimitives_) +
                                (skippedPrimitives_ == 1 ? " primitive" : " primitives") +
                                " of points or lines";
    if (scene_.instances.empty())
        fail("has no meshes to draw" +
             (skippedPrimitives_ ? " (" + skipped + " skipped: only triangles are drawn)" : std::string()));
    if (skippedPrimitives_) log::warn(path_ + ": " + skipped + " skipped; only triangles are drawn");
    scene_.updateBounds();
    return std::move(scene_);
}

// tinygltf decodes an image stored in a bufferView without checking that the view lies inside its
// buffer; this runs first, before a byte of it is read (a broken file: an error). `model` is the model being
// parsed, whose buffers and bufferViews are complete when images are reached.
bool loadImageInsideBuffer(tinygltf::Image* image, const int index, std::string* err, std::string* warn,
                           int width, int height, const unsigned char* bytes, int size, void* model) {
    if (image->bufferView >= 0) {
        const std::string problem =
            bufferViewRangeProblem(*static_cast<const tinygltf::Model*>(model), size_t(image->bufferView));
        if (!problem.empty() || size < 0) {
            *err += "image " + std::to_string(index) + ": " +
                    (problem.empty() ? "bufferView too large" : problem);
            return false;
        }
    }
    // Image data that cannot be decoded is what a missing image file is to tinygltf (a warning):
    // the materials that use it keep their flat factors, each named in a warning (GltfReader).
    std::string decodeError;
    if (!tinygltf::LoadImageData(image, index, &decodeError, warn, width, height, bytes, size, nullptr)) {
        *warn += "image " + std::to_string(index) + " cannot be decoded: " + decodeError;
        image->image.clear();
    }
    return true;
}

enum class GltfContainer { Json, Binary };

// Checked before tinygltf reads the file: it takes a directory for a file of unbounded size
// (std::bad_alloc) and does not say why an open failed.
GltfContainer probeGltfFile(const std::string& path) {
    std::error_code ec; // a path that cannot be examined is left to fopen, which says why
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (!ec && std::filesystem::is_directory(status))
        throw SceneError(path, "is a directory, not a glTF file");
    if (!ec && !std::filesystem::is_regular_file(status)) throw SceneError(path, "is not a regular file");
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file) throw SceneError(path, std::string("cannot open the file: ") + std::strerror(errno));
    char head[256] = {}; // the magic, or enough to see JSON past a byte order mark and white space
    const size_t read = std::fread(head, 1, sizeof(head), file);
    std::fclose(file);
    if (read >= 4 && std::string_view(head, 4) == "glTF") return GltfContainer::Binary;
    // A .glb that begins with neither the magic nor JSON (a glTF's JSON under a .glb name still
    // loads) would go to the JSON parser, whose error says nothing of the magic.
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    std::string_view start(head, read);
    if (start.starts_with("\xEF\xBB\xBF")) start.remove_prefix(3); // UTF-8 byte order mark
    const size_t first = start.find_first_not_of(" \t\r\n");
    const bool json = first != std::string_view::npos && start[first] == '{';
    if (extension == ".glb" && !json) {
        if (read == 0) throw SceneError(path, "is empty, not a binary glTF (GLB) file");
        std::string shown;
        for (size_t i = 0; i < std::min<size_t>(read, 4); ++i)
            shown += std::isprint(static_cast<unsigned char>(head[i])) ? head[i] : '?';
        throw SceneError(path, "is not a binary glTF (GLB) file: it begins with '" + shown +
                                   "', not the magic 'glTF'");
    }
    return GltfContainer::Json;
}

Scene readGltfFile(const std::string& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    loader.SetImageLoader(loadImageInsideBuffer, &model);
    std::string err, warn;
    const bool binary = probeGltfFile(path) == GltfContainer::Binary;
    checkGltfJson(path, binary, kSupportedExtensions);
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok) throw SceneError(path, "not a valid glTF 2.0 file: " + trimmed(err.empty() ? warn : err));
    validateGltf(path, model);
    // Image failures are warnings in tinygltf; they are reported per texture below.
    Scene scene = GltfReader(path, model).read();
    if (!warn.empty()) log::warn(path + ": " + trimmed(warn));
    return scene;
}

} // namespace

Scene loadGltf(const std::string& path) {
    try {
        return readGltfFile(path);
    } catch (const SceneError&) {
        throw;
    } catch (const std::exception& e) {
        // A failure the checks did not foresee (inside tinygltf, an allocation) still names the file.
        throw SceneError(path, std::string("could not be read: ") + e.what());
    }
}

Scene loadScene(std::string_view nameOrPath, float detail) {
    if (isBuiltinScene(nameOrPath)) return buildBuiltinScene(nameOrPath, detail);
    // A name that is neither (a misspelt "cornel", an empty one) would read as a missing file.
    std::error_code error;
    // Only where the path is known not to exist: another reason (no permission) is loadGltf's to name.
    if (nameOrPath.empty() ||
        (!std::filesystem::exists(std::filesystem::path(nameOrPath), error) && !error)) {
        std::string names;
        for (const std::string& n : builtinSceneNames())
            names += (names.empty() ? "" : ", ") + n;
        throw SceneError(nameOrPath.empty() ? std::string("''") : std::string(nameOrPath),
                         "neither a built-in scene (" + names + ") nor a file" +
                             (nameOrPath.empty() ? "" : ": No such file or directory"));
    }
    return loadGltf(std::string(nameOrPath));
}

} // namespace lpv::engine
