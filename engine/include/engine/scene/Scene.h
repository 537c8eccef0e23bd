// A scene as the renderer and the GI consume it: one vertex/index pool, meshes (index ranges with a
// material), instances placing meshes in the world, materials with textures, punctual lights and
// an optional camera. Built in code (Cornell box, atrium) or loaded from glTF 2.0.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace lpv::engine {

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec2 uv{0.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f}; // xyz tangent, w handedness
};

struct Bounds {
    glm::vec3 min{1e30f};
    glm::vec3 max{-1e30f};
    void add(glm::vec3 p);
    void add(const Bounds& b);
    bool empty() const { return min.x > max.x; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }
    float largestSide() const {
        const glm::vec3 s = size();
        return std::max(std::max(s.x, s.y), s.z);
    }
    Bounds transformed(const glm::mat4& m) const;
    // True when the box lies wholly outside the clip volume of `viewProjection` (-w <= x, y <= w,
    // 0 <= z <= w): what it bounds cannot reach that view. Conservative: a box that straddles a
    // corner of the volume counts as inside.
    bool outsideClipVolume(const glm::mat4& viewProjection) const;
};

// True when all of `points` lie beyond the same one of the six planes of `viewProjection`'s clip
// volume (Bounds::outsideClipVolume for a box's corners).
bool outsideClipVolume(std::span<const glm::vec3> points, const glm::mat4& viewProjection);

// RGBA8 pixels made in code or decoded from a file.
struct TextureImage {
    std::string name;
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba;
    bool srgb = true; // color data; normal and metallic-roughness maps are linear
};

struct Material {
    std::string name;
    glm::vec4 baseColor{1.0f};
    int32_t baseColorTexture = -1; // index into Scene::textures
    int32_t normalTexture = -1;
    float metallic = 0.0f;
    float roughness = 1.0f;
    int32_t metallicRoughnessTexture = -1; // linear: roughness in G, metallic in B (glTF)
    glm::vec3 emissive{0.0f};
    int32_t emissiveTexture = -1; // sRGB, times `emissive`
};

struct Mesh {
    std::string name;
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t material = 0;
    Bounds bounds; // object space
};

struct Instance {
    uint32_t mesh = 0;
    glm::mat4 transform{1.0f};
    Bounds worldBounds;
};

enum class LightType { Directional, Point, Spot };

struct Light {
    std::string name;
    LightType type = LightType::Directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f; // lux (directional) or candela (point, spot), as in KHR_lights_punctual
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // where the light travels
    float range = 0.0f;                     // 0: infinite
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.785398f;
};

struct Camera {
    glm::vec3 position{0.0f, 1.0f, 5.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFov = 0.8726646f; // radians (50 degrees)
    float nearPlane = 0.05f;
    float farPlane = 200.0f;
};

struct Scene {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;
    std::vector<Material> materials;
    std::vector<TextureImage> textures;
    std::vector<Light> lights;
    std::optional<Camera> camera;
    Bounds bounds; // world space, of all instances

    // Triangles drawn per frame (instances count their mesh every time).
    uint64_t triangleCount() const;
    // Recomputes instance world bounds and the scene bounds.
    void updateBounds();
};

// The scene's camera, or one in front of its bounds looking at their centre (for a glTF file
// without a camera): what the sample game shows and the reference renderer traces.
Camera defaultCamera(const Scene& scene);

} // namespace lpv::engine
