// Appends procedural geometry to a Scene: the shapes the built-in scenes are made of. Every
// primitive gets normals, UVs in world-ish units (so tiled textures keep their scale) and tangents.
#pragma once

#include "engine/scene/Scene.h"

#include <string>

namespace lpv::engine {

class MeshBuilder {
public:
    explicit MeshBuilder(Scene& scene) : scene_(scene) {}

    // Starts a mesh with `material`; shapes added until finish() belong to it. finish() adds an
    // instance with `transform` and returns the mesh index.
    void begin(std::string name, uint32_t material);
    uint32_t finish(const glm::mat4& transform = glm::mat4(1.0f));

    // A quad with corners origin, origin+u, origin+u+v, origin+v; faces along cross(u, v).
    // Subdivided into `su` x `sv` cells.
    void quad(glm::vec3 origin, glm::vec3 u, glm::vec3 v, uint32_t su = 1, uint32_t sv = 1,
              float uvScale = 1.0f);
    // Axis-aligned box from min to max, faces outward (inward when `inside`).
    void box(glm::vec3 min, glm::vec3 max, bool inside = false, float uvScale = 1.0f);
    // Vertical cylinder (y axis) of `radius`, from y0 to y1, with `segments` sides and caps.
    void cylinder(glm::vec3 base, float radius, float height, uint32_t segments, uint32_t rings = 1,
                  bool caps = true);
    // A surface of revolution around the y axis: profile points (radius, y), bottom to top.
    void lathe(glm::vec3 base, const std::vector<glm::vec2>& profile, uint32_t segments);
    // A semicircular arch in the plane spanned by x (width) and y, extruded along z by `depth`:
    // the intrados (underside) from (center.x - radius) to (center.x + radius), and its faces.
    void arch(glm::vec3 center, float radius, float thickness, float depth, uint32_t segments);
    // A hanging cloth: a grid in the xy plane (width x height, hanging down from `top`), waved along z.
    void cloth(glm::vec3 topLeft, float width, float height, uint32_t sx, uint32_t sy, float wave);

    // Adds raw triangles (positions and normals) as given; tangents and UVs are derived.
    void triangle(const Vertex& a, const Vertex& b, const Vertex& c);

private:
    uint32_t addVertex(const Vertex& v);
    void addTriangleIndices(uint32_t a, uint32_t b, uint32_t c);

    Scene& scene_;
    Mesh mesh_;
    uint32_t baseVertex_ = 0;
};

} // namespace lpv::engine
