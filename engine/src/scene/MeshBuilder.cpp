// Procedural shapes for the built-in scenes.
#include "engine/scene/MeshBuilder.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>

#include <cmath>

namespace lpv::engine {
namespace {

glm::vec4 tangentFor(glm::vec3 n) {
    // Any unit vector perpendicular to n; UVs of the shapes below follow it closely enough for
    // tiled detail normal maps.
    const glm::vec3 helper = std::fabs(n.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::vec4(glm::normalize(glm::cross(helper, n)), 1.0f);
}

} // namespace

void MeshBuilder::begin(std::string name, uint32_t material) {
    mesh_ = Mesh{};
    mesh_.name = std::move(name);
    mesh_.material = material;
    mesh_.firstIndex = uint32_t(scene_.indices.size());
    baseVertex_ = uint32_t(scene_.vertices.size());
}

uint32_t MeshBuilder::finish(const glm::mat4& transform) {
    mesh_.indexCount = uint32_t(scene_.indices.size()) - mesh_.firstIndex;
    const uint32_t index = uint32_t(scene_.meshes.size());
    scene_.meshes.push_back(mesh_);
    Instance inst;
    inst.mesh = index;
    inst.transform = transform;
    inst.worldBounds = mesh_.bounds.transformed(transform);
    scene_.instances.push_back(inst);
    scene_.bounds.add(inst.worldBounds);
    return index;
}

uint32_t MeshBuilder::addVertex(const Vertex& v) {
    mesh_.bounds.add(v.position);
    scene_.vertices.push_back(v);
    return uint32_t(scene_.vertices.size() - 1);
}

void MeshBuilder::addTriangleIndices(uint32_t a, uint32_t b, uint32_t c) {
    scene_.indices.insert(scene_.indices.end(), {a, b, c});
}

void MeshBuilder::triangle(const Vertex& a, const Vertex& b, const Vertex& c) {
    const uint32_t i = addVertex(a), j = addVertex(b), k = addVertex(c);
    addTriangleIndices(i, j, k);
}

void MeshBuilder::quad(glm::vec3 origin, glm::vec3 u, glm::vec3 v, uint32_t su, uint32_t sv, float uvScale) {
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    const glm::vec4 t(glm::normalize(u), 1.0f);
    const float lu = glm::length(u) * uvScale, lv = glm::length(v) * uvScale;
    const uint32_t first = uint32_t(scene_.vertices.size());
    for (uint32_t y = 0; y <= sv; ++y)
        for (uint32_t x = 0; x <= su; ++x) {
            const float fx = float(x) / float(su), fy = float(y) / float(sv);
            addVertex({origin + fx * u + fy * v, n, {fx * lu, fy * lv}, t});
        }
    for (uint32_t y = 0; y < sv; ++y)
        for (uint32_t x = 0; x < su; ++x) {
            const uint32_t i0 = first + y * (su + 1) + x, i1 = i0 + 1, i2 = i0 + su + 1, i3 = i2 + 1;
            addTriangleIndices(i0, i1, i3);
            addTriangleIndices(i0, i3, i2);
        }
}

void MeshBuilder::box(glm::vec3 mn, glm::vec3 mx, bool inside, float uvScale) {
    const glm::vec3 d = mx - mn;
    const glm::vec3 X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
    // Each face as (origin, u, v) with cross(u, v) pointing outward.
    struct Face {
        glm::vec3 o, u, v;
    };
    const Face faces[6] = {
        {mn, Z, Y},     // -x
        {mn + X, Y, Z}, // +x
        {mn, X, Z},     // -y
        {mn + Y, Z, X}, // +y
        {mn, Y, X},     // -z
        {mn + Z, X, Y}, // +z
    };
    for (const Face& f : faces) {
        if (inside)
            quad(f.o, f.v, f.u, 1, 1, uvScale);
        else
            quad(f.o, f.u, f.v, 1, 1, uvScale);
    }
}

void MeshBuilder::cylinder(glm::vec3 base, float radius, float height, uint32_t segments, uint32_t rings,
                           bool caps) {
    const float twoPi = glm::two_pi<float>();
    const uint32_t first = uint32_t(scene_.vertices.size());
    for (uint32_t r = 0; r <= rings; ++r)
        for (uint32_t s = 0; s <= segments; ++s) {
            const float a = twoPi * float(s) / float(segments);
            const glm::vec3 n(std::cos(a), 0.0f, std::sin(a));
            const float y = height * float(r) / float(rings);
            addVertex(
                {base + n * radius + glm::vec3(0, y, 0), n, {a * radius, y}, glm::vec4(-n.z, 0, n.x, 1)});
        }
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t i0 = first + r * (segments + 1) + s, i1 = i0 + 1, i2 = i0 + segments + 1,
                           i3 = i2 + 1;
            addTriangleIndices(i0, i2, i3);
            addTriangleIndices(i0, i3, i1);
        }
    if (!caps) return;
    for (int top = 0; top < 2; ++top) {
        const glm::vec3 n(0, top ? 1.0f : -1.0f, 0);
        const glm::vec3 c = base + glm::vec3(0, top ? height : 0.0f, 0);
        const uint32_t center = addVertex({c, n, {0, 0}, tangentFor(n)});
        const uint32_t ring = uint32_t(scene_.vertices.size());
        for (uint32_t s = 0; s <= segments; ++s) {
            const float a = twoPi * float(s) / float(segments);
            const glm::vec3 o(std::cos(a) * radius, 0, std::sin(a) * radius);
            addVertex({c + o, n, {o.x, o.z}, tangentFor(n)});
        }
        for (uint32_t s = 0; s < segments; ++s) {
            if (top)
                addTriangleIndices(center, ring + s + 1, ring + s);
            else
                addTriangleIndices(center, ring + s, ring + s + 1);
        }
    }
}

void MeshBuilder::lathe(glm::vec3 base, const std::vector<glm::vec2>& profile, uint32_t segments) {
    const float twoPi = glm::two_pi<float>();
    const uint32_t first = uint32_t(scene_.vertices.size());
    const uint32_t rows = uint32_t(profile.size());
    for (uint32_t r = 0; r < rows; ++r) {
        // Profile normal from neighbours: perpendicular to the profile's tangent in (radius, y).
        const glm::vec2 prev = profile[r > 0 ? r - 1 : r], next = profile[r + 1 < rows ? r + 1 : r];
        const glm::vec2 dir = glm::normalize(next - prev + glm::vec2(1e-6f, 0.0f));
        const glm::vec2 pn(dir.y, -dir.x);
        for (uint32_t s = 0; s <= segments; ++s) {
            const float a = twoPi * float(s) / float(segments);
            const glm::vec3 radial(std::cos(a), 0.0f, std::sin(a));
            const glm::vec3 n = glm::normalize(radial * pn.x + glm::vec3(0, pn.y, 0));
            addVertex({base + radial * profile[r].x + glm::vec3(0, profile[r].y, 0),
                       n,
                       {float(s) / float(segments) * 4.0f, profile[r].y},
                       glm::vec4(-radial.z, 0, radial.x, 1)});
        }
    }
    for (uint32_t r = 0; r + 1 < rows; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t i0 = first + r * (segments + 1) + s, i1 = i0 + 1, i2 = i0 + segments + 1,
                           i3 = i2 + 1;
            addTriangleIndices(i0, i2, i3);
            addTriangleIndices(i0, i3, i1);
        }
}

void MeshBuilder::arch(glm::vec3 center, float radius, float thickness, float depth, uint32_t segments) {
    const float pi = glm::pi<float>();
    const glm::vec3 dz(0, 0, depth);
    for (uint32_t s = 0; s < segments; ++s) {
        const float a0 = pi * float(s) / float(segments), a1 = pi * float(s + 1) / float(segments);
        const glm::vec3 r0(std::cos(a0), std::sin(a0), 0), r1(std::cos(a1), std::sin(a1), 0);
        const glm::vec3 in0 = center + r0 * radius, in1 = center + r1 * radius;
        const glm::vec3 out0 = center + r0 * (radius + thickness), out1 = center + r1 * (radius + thickness);
        // Underside (intrados): its normal points toward the arch's center.
        quad(in0 + dz, in1 - in0, -dz);
        // Front (-z) and back (+z) faces of the ring segment.
        for (int back = 0; back < 2; ++back) {
            const glm::vec3 n(0, 0, back ? 1.0f : -1.0f);
            const glm::vec3 off = back ? dz : glm::vec3(0.0f);
            const auto v = [&](glm::vec3 p) { return Vertex{p + off, n, {p.x, p.y}, {1, 0, 0, 1}}; };
            if (back) {
                triangle(v(in0), v(out0), v(out1));
                triangle(v(in0), v(out1), v(in1));
            } else {
                triangle(v(in0), v(out1), v(out0));
                triangle(v(in0), v(in1), v(out1));
            }
        }
    }
}

void MeshBuilder::cloth(glm::vec3 topLeft, float width, float height, uint32_t sx, uint32_t sy, float wave) {
    const uint32_t first = uint32_t(scene_.vertices.size());
    for (uint32_t y = 0; y <= sy; ++y)
        for (uint32_t x = 0; x <= sx; ++x) {
            const float fx = float(x) / float(sx), fy = float(y) / float(sy);
            const float phase = fx * 6.2831853f * 1.5f;
            // Folds deepen toward the free bottom edge.
            const float z = wave * std::sin(phase) * (0.3f + 0.7f * fy);
            const float dzdx = wave * std::cos(phase) * 6.2831853f * 1.5f / width * (0.3f + 0.7f * fy);
            const glm::vec3 n = glm::normalize(glm::vec3(-dzdx, 0.0f, 1.0f));
            addVertex({topLeft + glm::vec3(fx * width, -fy * height, z), n, {fx, fy}, tangentFor(n)});
        }
    for (uint32_t y = 0; y < sy; ++y)
        for (uint32_t x = 0; x < sx; ++x) {
            const uint32_t i0 = first + y * (sx + 1) + x, i1 = i0 + 1, i2 = i0 + sx + 1, i3 = i2 + 1;
            addTriangleIndices(i0, i2, i3);
            addTriangleIndices(i0, i3, i1);
        }
}

} // namespace lpv::engine
