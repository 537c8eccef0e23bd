// The built-in atrium: an open court in the spirit of the Sponza atrium, for GI and performance
// work at game scale. Everything is made here in code: geometry from MeshBuilder shapes, textures
// from ProceduralTextures.
//
// Layout (metres, y up). The court runs along x (30 m between the end walls) and is 12 m between
// the back walls. Along both long sides, two stories of arcades stand on the column lines
// z = +-3.5: ten semicircular arches per story on nine columns, springing from piers engaged in the
// end walls. The ground arcade carries a gallery floor at 5 m; the upper arcade has a balustrade
// between its columns and carries a wall band and a roof that covers both arcades. Over the court
// itself the roof is open, so the sun enters from above, lights a strip of the court floor and
// shines into the arcades on the -z side. Banners hang from the upper gallery and from the end
// walls; planters, a well, crates and vases stand about.
//
// Most triangles are in tessellation scaled by `detail` (columns, balusters, arches, vases, cloth,
// floor subdivision), so the object and instance counts do not change with it. Repeated parts
// (columns, arch bays, balustrades, vases) are one mesh each with many instances.
#include "ProceduralTextures.h"
#include "engine/scene/BuiltinScenes.h"
#include "engine/scene/MeshBuilder.h"

#include <glm/geometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace lpv::engine {
namespace {

// --- Layout ------------------------------------------------------------------------------------------

constexpr float kHalfLength = 15.0f; // inner faces of the end walls at x = +-kHalfLength
constexpr float kHalfWidth = 6.0f;   // inner faces of the back walls at z = +-kHalfWidth
constexpr float kWall = 0.4f;
constexpr float kColumnLine = 3.5f;
constexpr float kBay = 3.0f; // column spacing
constexpr int kBays = 10;    // arches per story and side; kBays * kBay = 2 * kHalfLength
// The arch ring's outer radius is half a bay, so neighbouring arches meet over the columns and the
// spandrels close flush with the crown.
constexpr float kArchRing = 0.3f, kArchRadius = kBay / 2.0f - kArchRing, kArchDepth = 0.6f;
constexpr float kCourtFace = kColumnLine - kArchDepth / 2.0f; // the arcades' face toward the court
constexpr float kGroundColumnHeight = 3.5f;
constexpr float kGalleryBottom = kGroundColumnHeight + kBay / 2.0f, kGalleryTop = kGalleryBottom + 0.3f;
constexpr float kUpperColumnHeight = 3.0f;
constexpr float kUpperCrown = kGalleryTop + kUpperColumnHeight + kBay / 2.0f;
constexpr float kRoofBottom = kUpperCrown + 0.2f, kRoofTop = kRoofBottom + 0.3f, kTop = kUpperCrown + 1.2f;
constexpr float kRailTop = kGalleryTop + 1.05f;

float bayCenter(int bay) {
    return -kHalfLength + kBay * (float(bay) + 0.5f);
}
float columnX(int column) {
    return -kHalfLength + kBay * float(column + 1);
} // 9 free-standing columns

enum MaterialId : uint32_t {
    kStone,
    kPlaster,
    kFloorTiles,
    kBrick,
    kFabricRed,
    kFabricGreen,
    kFabricBlue,
    kFabricYellow,
    kWood,
    kTerracotta,
    kBronze,
    kFoliage,
    kSoil,
    kRoof,
};

// Exact quarter turns about y: the two arcade sides are the same geometry turned half way round,
// and exact matrices keep mirrored parts coincident.
glm::mat4 turnY(int quarterTurns) {
    static constexpr float kCos[4] = {1, 0, -1, 0}, kSin[4] = {0, 1, 0, -1};
    const int q = ((quarterTurns % 4) + 4) % 4;
    glm::mat4 m(1.0f);
    m[0][0] = kCos[q];
    m[0][2] = -kSin[q];
    m[2][0] = kSin[q];
    m[2][2] = kCos[q];
    return m;
}

glm::mat4 at(glm::vec3 position, int quarterTurns = 0) {
    return glm::translate(glm::mat4(1.0f), position) * turnY(quarterTurns);
}

glm::mat4 atAngle(glm::vec3 position, float degrees) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), position), glm::radians(degrees), {0, 1, 0});
}

// Geometry for the -z arcade is built in world space; turning it half way round gives the +z one.
// Per-bay parts use a frame at the column line whose +z points into the court.
const std::array<glm::mat4, 2> kSides = {turnY(0), turnY(2)};

glm::mat4 onSide(int side, float x, float y) {
    return kSides[size_t(side)] * glm::translate(glm::mat4(1.0f), {x, y, -kColumnLine});
}

// --- Tessellation --------------------------------------------------------------------------------

// Both directions of a 2D tessellation grow with detail^0.6, so triangle counts grow about
// linearly with detail (a little faster, which makes up for the rows of profiles that do not scale).
// Arcs tessellated in one direction only use `linear`.
struct Tessellation {
    float scale;
    float detail;
    uint32_t operator()(float base, uint32_t minimum) const {
        return std::max(minimum, uint32_t(std::lround(base * scale)));
    }
    uint32_t linear(float base, uint32_t minimum) const {
        return std::max(minimum, uint32_t(std::lround(base * detail)));
    }
};

// --- Building blocks ---------------------------------------------------------------------------

// Ends the mesh with one instance per transform (MeshBuilder::finish places only the first).
uint32_t finishInstances(MeshBuilder& b, Scene& scene, const std::vector<glm::mat4>& transforms) {
    const uint32_t mesh = b.finish(transforms.front());
    for (size_t i = 1; i < transforms.size(); ++i)
        scene.instances.push_back(
            {mesh, transforms[i], scene.meshes[mesh].bounds.transformed(transforms[i])});
    return mesh;
}

// A box whose top face is subdivided (floors: the tiles get vertices for per-vertex effects and
// the tessellation budget scales with detail).
void slab(MeshBuilder& b, glm::vec3 mn, glm::vec3 mx, uint32_t cellsX, uint32_t cellsZ,
          float uvScale = 1.0f) {
    const glm::vec3 d = mx - mn;
    const glm::vec3 X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
    b.quad(mn + Y, Z, X, cellsZ, cellsX, uvScale); // top
    b.quad(mn, X, Z, 1, 1, uvScale);               // bottom
    b.quad(mn, Z, Y, 1, 1, uvScale);               // -x
    b.quad(mn + X, Y, Z, 1, 1, uvScale);           // +x
    b.quad(mn, Y, X, 1, 1, uvScale);               // -z
    b.quad(mn + Z, X, Y, 1, 1, uvScale);           // +z
}

// A lathe profile (radius, y), bottom to top, assembled from mouldings.
class Profile {
public:
    explicit Profile(glm::vec2 start) { points_.push_back(start); }

    Profile& lineTo(glm::vec2 to, uint32_t steps = 1) {
        const glm::vec2 from = points_.back();
        for (uint32_t i = 1; i <= steps; ++i)
            points_.push_back(glm::mix(from, to, float(i) / float(steps)));
        return *this;
    }
    // A half-round moulding on the chord from the current point to `to`: a torus bulging outward,
    // or a scotia (hollow) bulging inward.
    Profile& roundTo(glm::vec2 to, bool outward, uint32_t steps) {
        const glm::vec2 from = points_.back(), mid = 0.5f * (from + to), half = 0.5f * (to - from);
        const glm::vec2 bulge = glm::vec2(half.y, -half.x) * (outward ? 1.0f : -1.0f);
        for (uint32_t i = 1; i <= steps; ++i) {
            const float a = glm::pi<float>() * float(i) / float(steps);
            points_.push_back(mid - half * std::cos(a) + bulge * std::sin(a));
        }
        return *this;
    }
    // Points shape(t) for t in (0, 1]; shape(0) should be the current point.
    template <class Shape> Profile& curve(Shape&& shape, uint32_t steps) {
        for (uint32_t i = 1; i <= steps; ++i)
            points_.push_back(shape(float(i) / float(steps)));
        return *this;
    }
    const std::vector<glm::vec2>& points() const { return points_; }

private:
    std::vector<glm::vec2> points_;
};

// A Tuscan column: square plinth, moulded base, a shaft with entasis, astragal, echinus and a square
// abacus as wide as the arches' springing (0.6 m). Base at y = 0.
void column(MeshBuilder& b, float height, float radius, const Tessellation& tess) {
    constexpr float plinth = 0.2f, abacus = 0.2f, capital = 0.42f;
    const float shaftBottom = plinth + 0.36f, shaftTop = height - abacus - capital, top = radius * 0.86f;
    b.box({-radius - 0.12f, 0.0f, -radius - 0.12f}, {radius + 0.12f, plinth, radius + 0.12f}, false, 0.5f);
    Profile p({radius + 0.07f, plinth});
    p.roundTo({radius + 0.07f, plinth + 0.16f}, true, tess(10, 3))
        .lineTo({radius + 0.03f, plinth + 0.17f})
        .roundTo({radius + 0.03f, plinth + 0.25f}, false, tess(7, 2))
        .lineTo({radius + 0.04f, plinth + 0.26f})
        .roundTo({radius + 0.04f, plinth + 0.34f}, true, tess(7, 2))
        .lineTo({radius, shaftBottom})
        .curve(
            [&](float t) {
                // Entasis: a slight swelling in the lower third, then a taper to 86%.
                const float r =
                    radius *
                    (1.0f + 0.035f * std::sin(glm::pi<float>() * std::min(1.0f, t * 1.5f)) - 0.14f * t);
                return glm::vec2(r, glm::mix(shaftBottom, shaftTop, t));
            },
            tess(14, 2))
        .roundTo({top, shaftTop + 0.07f}, true, tess(6, 2))
        .lineTo({top - 0.01f, shaftTop + 0.09f})
        .lineTo({top - 0.01f, shaftTop + 0.18f})
        .curve(
            [&](float t) {
                // Echinus: a quarter round swelling out under the abacus.
                const float a = 0.5f * glm::pi<float>() * t;
                return glm::vec2(top - 0.01f + (0.29f - top + 0.01f) * std::sin(a),
                                 shaftTop + 0.18f + (capital - 0.18f) * (1.0f - std::cos(a)));
            },
            tess(9, 2));
    b.lathe({0, 0, 0}, p.points(), tess(24, 8));
    b.box({-0.3f, height - abacus, -kArchDepth / 2.0f}, {0.3f, height, kArchDepth / 2.0f}, false, 0.5f);
}

// The spandrels of one bay: the wall between the arch ring's extrados and the bay's rectangle, on
// the front (+z) and back (-z) faces. Fans from the rectangle's top corners to the extrados, on the
// same angles as MeshBuilder::arch so the edges match.
void spandrels(MeshBuilder& b, float halfSpan, float depth, uint32_t segments) {
    const float r = halfSpan;
    for (int back = 0; back < 2; ++back) {
        const float z = back ? -depth / 2.0f : depth / 2.0f;
        const glm::vec3 n(0, 0, back ? -1.0f : 1.0f);
        // uv follows (x, y); on the back face +u runs along +x with the bitangent flipped.
        const glm::vec4 t(1, 0, 0, back ? -1.0f : 1.0f);
        const auto v = [&](float x, float y) { return Vertex{{x, y, z}, n, {x, y}, t}; };
        for (int right = 0; right < 2; ++right) {
            const float cx = right ? r : -r;
            for (uint32_t s = 0; s < segments / 2; ++s) {
                // Angles from the crown (pi/2) toward this half's springing.
                const uint32_t k0 = right ? segments / 2 - s : segments / 2 + s;
                const uint32_t k1 = right ? k0 - 1 : k0 + 1;
                const float a0 = glm::pi<float>() * float(k0) / float(segments);
                const float a1 = glm::pi<float>() * float(k1) / float(segments);
                const Vertex c = v(cx, r), p0 = v(r * std::cos(a0), r * std::sin(a0)),
                             p1 = v(r * std::cos(a1), r * std::sin(a1));
                // Counter-clockwise seen from the face's normal.
                if ((back != 0) != (right != 0))
                    b.triangle(c, p0, p1);
                else
                    b.triangle(c, p1, p0);
            }
        }
    }
}

// One bay of balustrade between upper columns: plinth, rail and vase-shaped balusters. Centred on
// x = 0 at the column line, standing on y = 0.
void balustrade(MeshBuilder& b, const Tessellation& tess) {
    constexpr float halfLength = kBay / 2.0f - 0.3f, plinth = 0.15f, rail = 0.15f;
    constexpr float height = kRailTop - kGalleryTop;
    constexpr int balusters = 8;
    b.box({-halfLength, 0.0f, -0.17f}, {halfLength, plinth, 0.17f}, false, 0.5f);
    b.box({-halfLength, height - rail, -0.2f}, {halfLength, height, 0.2f}, false, 0.5f);
    const float h = height - rail - plinth;
    Profile p({0.055f, 0.0f});
    p.lineTo({0.055f, 0.03f * h})
        .roundTo({0.055f, 0.1f * h}, true, tess(4, 1))
        .lineTo({0.035f, 0.16f * h})
        .curve(
            [&](float t) {
                return glm::vec2(0.035f + 0.04f * std::sin(glm::pi<float>() * std::pow(t, 0.7f)),
                                 glm::mix(0.16f * h, 0.72f * h, t));
            },
            tess(9, 2))
        .roundTo({0.035f, 0.8f * h}, true, tess(3, 1))
        .lineTo({0.05f, 0.95f * h})
        .lineTo({0.05f, h});
    for (int i = 0; i < balusters; ++i) {
        const float x = -halfLength + (float(i) + 0.5f) * (2.0f * halfLength / float(balusters));
        b.lathe({x, plinth, 0.0f}, p.points(), tess(10, 4));
    }
}

// A palm-like frond: a strip curving out from `base` along `azimuth`, rising then drooping, widest
// at mid-length and ending in a point.
void frond(MeshBuilder& b, glm::vec3 base, float azimuth, float length, float rise, float droop, float width,
           uint32_t segments) {
    const glm::vec3 dir(std::cos(azimuth), 0.0f, std::sin(azimuth)), side(-dir.z, 0.0f, dir.x), up(0, 1, 0);
    const auto centre = [&](float t) { return base + dir * (length * t) + up * (rise * t - droop * t * t); };
    const auto edge = [&](float t, float s) {
        const glm::vec3 tangent = glm::normalize(dir * length + up * (rise - 2.0f * droop * t));
        const glm::vec3 n = glm::normalize(glm::cross(side, tangent));
        const float w = 0.5f * width * std::sin(glm::pi<float>() * (0.15f + 0.85f * t));
        return Vertex{centre(t) + side * (s * w) + n * (0.02f * (1.0f - std::fabs(s))),
                      n,
                      {s * w, t * length},
                      glm::vec4(tangent, 1.0f)};
    };
    for (uint32_t i = 0; i + 1 < segments; ++i) {
        const float t0 = float(i) / float(segments), t1 = float(i + 1) / float(segments);
        const Vertex l0 = edge(t0, -1.0f), r0 = edge(t0, 1.0f), l1 = edge(t1, -1.0f), r1 = edge(t1, 1.0f);
        b.triangle(l0, r0, r1);
        b.triangle(l0, r1, l1);
    }
    const float tl = float(segments - 1) / float(segments);
    Vertex tip = edge(1.0f, 0.0f);
    tip.position = centre(1.0f);
    b.triangle(edge(tl, -1.0f), edge(tl, 1.0f), tip);
}

// --- The scene, part by part -------------------------------------------------------------------

void addMaterialsAndTextures(Scene& scene) {
    enum : int32_t {
        tStone,
        tPlaster,
        tTiles,
        tTilesN,
        tBrick,
        tBrickN,
        tWood,
        tRed,
        tGreen,
        tBlue,
        tYellow
    };
    const glm::vec3 gold(0.86f, 0.68f, 0.30f);
    scene.textures = {
        textures::stoneAlbedo(256),
        textures::plasterAlbedo(256),
        textures::floorTilesAlbedo(512),
        textures::floorTilesNormal(512),
        textures::brickAlbedo(256),
        textures::brickNormal(256),
        textures::woodAlbedo(256),
        textures::bannerFabric({0.62f, 0.07f, 0.06f}, gold, 0, 192, 512),
        textures::bannerFabric({0.10f, 0.38f, 0.14f}, gold, 1, 192, 512),
        textures::bannerFabric({0.09f, 0.16f, 0.48f}, gold, 2, 192, 512),
        textures::bannerFabric({0.86f, 0.66f, 0.12f}, {0.50f, 0.08f, 0.06f}, 3, 192, 512),
    };
    const auto textured = [](const char* name, int32_t texture, float roughness,
                             glm::vec3 tint = glm::vec3(1.0f)) {
        Material m;
        m.name = name;
        m.baseColor = glm::vec4(tint, 1.0f);
        m.baseColorTexture = texture;
        m.roughness = roughness;
        return m;
    };
    scene.materials.resize(kRoof + 1);
    scene.materials[kStone] = textured("stone", tStone, 0.7f);
    scene.materials[kPlaster] = textured("plaster", tPlaster, 0.9f, {0.95f, 0.9f, 0.82f});
    scene.materials[kFloorTiles] = textured("floor tiles", tTiles, 0.35f); // polished marble
    scene.materials[kFloorTiles].normalTexture = tTilesN;
    scene.materials[kBrick] = textured("brick", tBrick, 0.85f);
    scene.materials[kBrick].normalTexture = tBrickN;
    scene.materials[kFabricRed] = textured("fabric red", tRed, 0.95f);
    scene.materials[kFabricGreen] = textured("fabric green", tGreen, 0.95f);
    scene.materials[kFabricBlue] = textured("fabric blue", tBlue, 0.95f);
    scene.materials[kFabricYellow] = textured("fabric yellow", tYellow, 0.95f);
    scene.materials[kWood] = textured("wood", tWood, 0.75f);
    scene.materials[kTerracotta] = textured("terracotta", tPlaster, 0.8f, {0.78f, 0.42f, 0.27f});
    scene.materials[kBronze] = textured("bronze", -1, 0.35f, {0.80f, 0.50f, 0.26f});
    scene.materials[kBronze].metallic = 1.0f;
    scene.materials[kFoliage] = textured("foliage", -1, 0.7f, {0.16f, 0.36f, 0.10f});
    scene.materials[kSoil] = textured("soil", -1, 1.0f, {0.22f, 0.15f, 0.10f});
    scene.materials[kRoof] = textured("roof", tPlaster, 0.9f, {0.80f, 0.76f, 0.70f});
}

// Floors, walls, gallery slab and roof: solid slabs, so light cannot leak through them.
void addShell(MeshBuilder& b, Scene& scene, const Tessellation& tess) {
    const float outX = kHalfLength + kWall, outZ = kHalfWidth + kWall;
    const std::vector<glm::mat4> bothSides(kSides.begin(), kSides.end());

    b.begin("court floor", kFloorTiles);
    slab(b, {-outX, -0.3f, -outZ}, {outX, 0.0f, outZ}, tess(124, 8), tess(52, 4));
    b.finish();

    b.begin("end wall", kBrick);
    b.box({kHalfLength, 0.0f, -outZ}, {outX, kTop, outZ});
    finishInstances(b, scene, {at({0, 0, 0}), at({0, 0, 0}, 2)});

    b.begin("back wall lower", kPlaster);
    b.box({-outX, 0.0f, -outZ}, {outX, kGalleryTop, -kHalfWidth}, false, 0.5f);
    finishInstances(b, scene, bothSides);
    b.begin("back wall upper", kBrick);
    b.box({-outX, kGalleryTop, -outZ}, {outX, kTop, -kHalfWidth});
    finishInstances(b, scene, bothSides);

    // Pilasters on the back walls answer the columns; piers in the end walls carry the end arches.
    b.begin("pilasters and piers", kStone);
    for (int c = 0; c < kBays - 1; ++c) {
        const float x = columnX(c);
        b.box({x - 0.25f, 0.0f, -kHalfWidth}, {x + 0.25f, kGalleryBottom, -kHalfWidth + 0.15f}, false, 0.5f);
        b.box({x - 0.25f, kGalleryTop, -kHalfWidth}, {x + 0.25f, kRoofBottom, -kHalfWidth + 0.15f}, false,
              0.5f);
    }
    for (float s : {-1.0f, 1.0f}) {
        const float x0 = s * kHalfLength, x1 = s * (kHalfLength - kArchRing);
        const glm::vec3 lo(std::min(x0, x1), 0.0f, -kColumnLine - kArchDepth / 2.0f);
        const glm::vec3 hi(std::max(x0, x1), kGroundColumnHeight, -kCourtFace);
        b.box(lo, hi, false, 0.5f);
        b.box(lo + glm::vec3(0, kGalleryTop, 0), hi + glm::vec3(0, kGalleryTop, 0), false, 0.5f);
    }
    finishInstances(b, scene, bothSides);

    b.begin("gallery slab", kStone);
    b.box({-kHalfLength, kGalleryBottom, -kHalfWidth}, {kHalfLength, kGalleryTop - 0.02f, -kCourtFace}, false,
          0.5f);
    // A string course marks the gallery floor on the court face.
    b.box({-kHalfLength, kGalleryBottom - 0.05f, -kCourtFace},
          {kHalfLength, kGalleryTop + 0.05f, -kCourtFace + 0.12f}, false, 0.5f);
    finishInstances(b, scene, bothSides);
    b.begin("gallery floor", kFloorTiles);
    slab(b, {-kHalfLength, kGalleryTop - 0.02f, -kHalfWidth}, {kHalfLength, kGalleryTop, -kCourtFace},
         tess(60, 4), tess(12, 1));
    finishInstances(b, scene, bothSides);

    // The wall band over the upper arcade hides the roof's edge; its cornice overhangs the court.
    b.begin("wall band", kPlaster);
    b.box({-kHalfLength, kUpperCrown, -kColumnLine - kArchDepth / 2.0f},
          {kHalfLength, kTop - 0.2f, -kCourtFace}, false, 0.5f);
    finishInstances(b, scene, bothSides);
    b.begin("cornice", kStone);
    b.box({-kHalfLength, kTop - 0.2f, -kColumnLine - 0.45f}, {kHalfLength, kTop, -kCourtFace + 0.2f}, false,
          0.5f);
    finishInstances(b, scene, bothSides);

    b.begin("roof", kRoof);
    b.box({-outX, kRoofBottom, -outZ}, {outX, kRoofTop, -kColumnLine - kArchDepth / 2.0f}, false, 0.5f);
    finishInstances(b, scene, bothSides);
}

void addArcades(MeshBuilder& b, Scene& scene, const Tessellation& tess) {
    std::vector<glm::mat4> ground, upper;
    for (int side = 0; side < 2; ++side)
        for (int c = 0; c < kBays - 1; ++c) {
            ground.push_back(onSide(side, columnX(c), 0.0f));
            upper.push_back(onSide(side, columnX(c), kGalleryTop));
        }
    b.begin("column", kStone);
    column(b, kGroundColumnHeight, 0.22f, tess);
    finishInstances(b, scene, ground);
    b.begin("upper column", kStone);
    column(b, kUpperColumnHeight, 0.19f, tess);
    finishInstances(b, scene, upper);

    std::vector<glm::mat4> bays, upperBays;
    for (int side = 0; side < 2; ++side)
        for (int bay = 0; bay < kBays; ++bay) {
            bays.push_back(onSide(side, bayCenter(bay), kGroundColumnHeight));
            bays.push_back(onSide(side, bayCenter(bay), kGalleryTop + kUpperColumnHeight));
            upperBays.push_back(onSide(side, bayCenter(bay), kGalleryTop));
        }
    const uint32_t segments = (tess.linear(40, 6) + 1) / 2 * 2; // even: spandrels split at the crown
    b.begin("arch", kStone);
    b.arch({0.0f, 0.0f, -kArchDepth / 2.0f}, kArchRadius, kArchRing, kArchDepth, segments);
    finishInstances(b, scene, bays);
    b.begin("spandrels", kPlaster);
    spandrels(b, kBay / 2.0f, kArchDepth, segments);
    finishInstances(b, scene, bays);

    b.begin("balustrade", kStone);
    balustrade(b, tess);
    finishInstances(b, scene, upperBays);
}

void addBanners(MeshBuilder& b, Scene& scene, const Tessellation& tess) {
    // Gallery banners hang in front of the balustrade from rods resting on its rail; each colour
    // appears once on each side.
    constexpr float width = 1.6f, height = 4.2f, offset = 0.55f; // in front of the column line
    const std::array<uint32_t, 4> fabrics = {kFabricRed, kFabricBlue, kFabricGreen, kFabricYellow};
    const std::array<int, 4> bays = {1, 3, 6, 8};
    std::vector<glm::mat4> rods;
    for (size_t f = 0; f < fabrics.size(); ++f) {
        std::vector<glm::mat4> places;
        for (int side = 0; side < 2; ++side) {
            const int bay = bays[(f + size_t(side) * 2) % bays.size()];
            places.push_back(onSide(side, bayCenter(bay), kRailTop) * at({0, 0, offset}));
            rods.push_back(places.back());
        }
        b.begin(scene.materials[fabrics[f]].name + " banner", fabrics[f]);
        b.cloth({-width / 2.0f, 0.0f, 0.0f}, width, height, tess(20, 3), tess(56, 6),
                0.06f + 0.01f * float(f));
        finishInstances(b, scene, places);
    }
    b.begin("banner rod", kBronze);
    b.box({-width / 2.0f - 0.05f, -0.02f, -0.025f}, {width / 2.0f + 0.05f, 0.04f, 0.025f});
    for (float x : {-0.6f, 0.6f})
        b.box({x - 0.02f, 0.0f, -offset + 0.2f}, {x + 0.02f, 0.04f, -0.025f});
    finishInstances(b, scene, rods);

    // Two long banners on the end walls, facing down the court.
    constexpr float endWidth = 2.0f, endHeight = 6.0f, endTop = kUpperCrown - 0.8f, fromWall = 0.2f;
    const glm::mat4 eastWall = at({kHalfLength - fromWall, endTop, 0.0f}, -1);
    const glm::mat4 westWall = at({-kHalfLength + fromWall, endTop, 0.0f}, 1);
    for (const auto& [fabric, place] : {std::pair{kFabricRed, eastWall}, std::pair{kFabricBlue, westWall}}) {
        b.begin(scene.materials[fabric].name + " end banner", fabric);
        b.cloth({-endWidth / 2.0f, 0.0f, 0.0f}, endWidth, endHeight, tess(24, 3), tess(72, 6), 0.07f);
        b.finish(place);
    }
    b.begin("end banner rod", kBronze);
    b.box({-endWidth / 2.0f - 0.08f, -0.02f, -0.03f}, {endWidth / 2.0f + 0.08f, 0.05f, 0.03f});
    for (float x : {-0.8f, 0.8f})
        b.box({x - 0.025f, 0.0f, -fromWall}, {x + 0.025f, 0.05f, -0.03f});
    finishInstances(b, scene, {eastWall, westWall});
}

void addPlanters(MeshBuilder& b, Scene& scene, const Tessellation& tess) {
    const std::vector<glm::mat4> places = {atAngle({-8.5f, 0, -1.9f}, 0), atAngle({-8.5f, 0, 1.9f}, 40),
                                           atAngle({8.5f, 0, -1.9f}, 80), atAngle({8.5f, 0, 1.9f}, 120)};
    constexpr float soil = 0.62f, trunkTop = 1.7f;
    b.begin("planter pot", kTerracotta);
    Profile pot({0.42f, 0.0f});
    pot.lineTo({0.47f, 0.06f})
        .curve([](float t) { return glm::vec2(0.47f + 0.11f * std::sqrt(t), 0.06f + 0.54f * t); },
               tess(10, 2))
        .roundTo({0.58f, 0.72f}, true, tess(8, 2))
        .lineTo({0.54f, 0.72f})
        .lineTo({0.53f, soil});
    b.lathe({0, 0, 0}, pot.points(), tess(36, 8));
    finishInstances(b, scene, places);

    b.begin("planter soil", kSoil);
    b.cylinder({0, soil - 0.04f, 0}, 0.535f, 0.04f, tess(36, 8), 1, true);
    finishInstances(b, scene, places);

    b.begin("palm trunk", kWood);
    b.cylinder({0, soil, 0}, 0.07f, trunkTop - soil, tess(12, 5), tess(6, 1), false);
    finishInstances(b, scene, places);

    // Two tiers of fronds at golden-angle spacing, so no two overlap exactly.
    b.begin("palm fronds", kFoliage);
    const uint32_t segments = tess(12, 3);
    for (int i = 0; i < 16; ++i) {
        const bool upperTier = i < 9;
        const float azimuth = 2.39996f * float(i);
        frond(b, {0, upperTier ? trunkTop : trunkTop - 0.25f, 0}, azimuth, upperTier ? 1.2f : 0.95f,
              upperTier ? 0.6f : 0.35f, upperTier ? 1.2f : 0.9f, 0.3f, segments);
    }
    finishInstances(b, scene, places);

    // A stone well head in the middle of the court.
    b.begin("well", kStone);
    Profile well({1.30f, 0.0f});
    well.lineTo({1.34f, 0.06f})
        .lineTo({1.24f, 0.12f})
        .lineTo({1.20f, 0.55f}, tess(3, 1))
        .roundTo({1.20f, 0.72f}, true, tess(8, 2))
        .lineTo({1.05f, 0.74f}, tess(2, 1))
        .lineTo({1.02f, 0.70f})
        .lineTo({1.00f, 0.25f}, tess(3, 1))
        .lineTo({0.12f, 0.25f}, tess(4, 1))
        .lineTo({0.10f, 0.10f});
    b.lathe({0, 0, 0}, well.points(), tess(64, 12));
    b.finish();
}

void addClutter(MeshBuilder& b, Scene& scene, const Tessellation& tess) {
    // Crates: a board box with an edge frame, in stacks in the court and at the ends of the arcades.
    b.begin("crate", kWood);
    constexpr float s = 0.8f, f = 0.07f;
    b.box({f / 2, f / 2, f / 2}, {s - f / 2, s - f / 2, s - f / 2});
    for (int axis = 0; axis < 3; ++axis)
        for (int corner = 0; corner < 4; ++corner) {
            glm::vec3 lo(0.0f), hi(s);
            const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            lo[a1] = (corner & 1) ? s - f : 0.0f;
            hi[a1] = lo[a1] + f;
            lo[a2] = (corner & 2) ? s - f : 0.0f;
            hi[a2] = lo[a2] + f;
            b.box(lo, hi);
        }
    finishInstances(
        b, scene,
        {atAngle({5.6f, 0, -2.7f}, 8), atAngle({6.65f, 0, -2.6f}, -4), atAngle({6.0f, s, -2.5f}, 27),
         atAngle({-5.2f, 0, 2.0f}, -12), atAngle({-4.3f, 0, 2.3f}, 3), atAngle({-14.2f, 0, 4.6f}, 0),
         atAngle({-14.2f, s, 4.7f}, 10), atAngle({13.4f, 0, -5.2f}, 15), atAngle({12.5f, 0, -5.4f}, 0)});

    // Vases along the back walls of both arcades, a tall amphora and a wide urn.
    const uint32_t segments = tess(28, 8);
    b.begin("amphora", kTerracotta);
    Profile amphora({0.11f, 0.0f});
    amphora.lineTo({0.12f, 0.03f})
        .lineTo({0.08f, 0.09f}, tess(2, 1))
        .curve(
            [](float t) {
                return glm::vec2(0.08f + 0.17f * std::sin(glm::pi<float>() * std::pow(t, 0.75f)) + 0.02f * t,
                                 0.09f + 0.66f * t);
            },
            tess(16, 4))
        .lineTo({0.08f, 0.86f}, tess(3, 1))
        .roundTo({0.08f, 0.93f}, true, tess(5, 2))
        .lineTo({0.065f, 0.93f})
        .lineTo({0.06f, 0.84f});
    b.lathe({0, 0, 0}, amphora.points(), segments);
    std::vector<glm::mat4> amphorae, urns;
    for (int side = 0; side < 2; ++side) {
        for (int bay : {0, 2, 5, 7})
            amphorae.push_back(onSide(side, bayCenter(bay), 0.0f) * at({0, 0, -2.0f}));
        for (int bay : {4, 9})
            urns.push_back(onSide(side, bayCenter(bay), 0.0f) * at({0, 0, -2.0f}));
        for (int bay : {1, 8})
            urns.push_back(onSide(side, bayCenter(bay), kGalleryTop) * at({0, 0, -2.0f}));
    }
    finishInstances(b, scene, amphorae);

    b.begin("urn", kBronze);
    Profile urn({0.14f, 0.0f});
    urn.lineTo({0.16f, 0.04f})
        .lineTo({0.10f, 0.1f}, tess(2, 1))
        .curve(
            [](float t) {
                return glm::vec2(0.10f + 0.22f * std::sin(glm::pi<float>() * (0.15f + 0.7f * t)),
                                 0.1f + 0.42f * t);
            },
            tess(14, 4))
        .lineTo({0.2f, 0.6f}, tess(2, 1))
        .roundTo({0.2f, 0.66f}, true, tess(5, 2))
        .lineTo({0.18f, 0.66f})
        .lineTo({0.17f, 0.56f});
    b.lathe({0, 0, 0}, urn.points(), segments);
    finishInstances(b, scene, urns);
}

void addLightAndCamera(Scene& scene) {
    // The sun comes from high over the +z roof, slightly from -x: it lights a strip of the court
    // floor along the -z arcade and reaches into that arcade through its arches on both stories.
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    sun.color = {1.0f, 0.95f, 0.88f};
    sun.intensity = 20.0f;
    scene.lights.push_back(sun);

    Camera cam;
    cam.position = {-kHalfLength + 2.0f, 1.7f, 0.0f};
    cam.forward = glm::normalize(glm::vec3(1.0f, 0.04f, 0.0f));
    cam.verticalFov = glm::radians(60.0f);
    cam.nearPlane = 0.1f;
    cam.farPlane = 100.0f;
    scene.camera = cam;
}

} // namespace

Light atriumCourtSpot() {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 8.0f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.6f));
    spot.outerConeAngle = 0.7f;
    spot.innerConeAngle = 0.5f;
    spot.intensity = 100.0f;
    return spot;
}

Scene buildAtrium(float detail) {
    // Below 0.05 nothing recognisable is left; NaN lands here too.
    if (!(detail >= 0.05f)) detail = 0.05f;
    const Tessellation tess{std::pow(detail, 0.6f), detail};

    Scene scene;
    scene.name = "atrium";
    addMaterialsAndTextures(scene);
    MeshBuilder b(scene);
    addShell(b, scene, tess);
    addArcades(b, scene, tess);
    addBanners(b, scene, tess);
    addPlanters(b, scene, tess);
    addClutter(b, scene, tess);
    addLightAndCamera(scene);
    scene.updateBounds();
    return scene;
}

} // namespace lpv::engine
