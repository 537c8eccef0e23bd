// The Embree side of the reference: one triangle geometry per instance, in world space (flattened
// rather than Embree instances: the scenes are small, and hits then need no per-level transforms),
// and the material lookup at a hit (base colour texture decoded once to linear floats).
#include "reference/RayScene.h"

#include <embree3/rtcore.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lpv::reference {
namespace {

// A texture as linear floats, sampled bilinearly with repeat wrapping (the engine's sampler).
struct LinearTexture {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec4> texels;

    glm::vec4 at(int x, int y) const {
        const int w = int(width), h = int(height);
        x %= w;
        y %= h;
        if (x < 0) x += w;
        if (y < 0) y += h;
        return texels[size_t(y) * width + size_t(x)];
    }
    glm::vec4 sample(glm::vec2 uv) const {
        const float fx = uv.x * float(width) - 0.5f, fy = uv.y * float(height) - 0.5f;
        const float x0 = std::floor(fx), y0 = std::floor(fy);
        const float tx = fx - x0, ty = fy - y0;
        // Wrapped in float first: a UV far from [0, 1] must not overflow the int.
        const int ix = int(std::fmod(x0, float(width))), iy = int(std::fmod(y0, float(height)));
        const glm::vec4 top = (1.0f - tx) * at(ix, iy) + tx * at(ix + 1, iy);
        const glm::vec4 bottom = (1.0f - tx) * at(ix, iy + 1) + tx * at(ix + 1, iy + 1);
        return (1.0f - ty) * top + ty * bottom;
    }
};

LinearTexture decode(const engine::TextureImage& image) {
    float table[256];
    for (int i = 0; i < 256; ++i) {
        const float c = float(i) / 255.0f;
        table[i] = image.srgb ? (c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f)) : c;
    }
    LinearTexture t;
    t.width = image.width;
    t.height = image.height;
    t.texels.resize(size_t(image.width) * image.height);
    for (size_t i = 0; i < t.texels.size(); ++i)
        // Alpha (and metallic in B of a linear map) stays linear.
        t.texels[i] = {table[image.rgba[i * 4]], table[image.rgba[i * 4 + 1]], table[image.rgba[i * 4 + 2]],
                       float(image.rgba[i * 4 + 3]) / 255.0f};
    return t;
}

struct Geometry {
    uint32_t instance = 0;
    uint32_t firstIndex = 0; // into Scene::indices
    int32_t vertexOffset = 0;
    uint32_t material = 0;
    glm::mat3 normalMatrix{1.0f};     // inverse transpose of the instance transform
    std::vector<glm::vec3> positions; // world space, indexed by local index (see below)
    uint32_t minIndex = 0;            // local index = Scene index - minIndex
};

} // namespace

struct RayScene::Impl {
    const engine::Scene* scene = nullptr;
    RTCDevice device = nullptr;
    RTCScene rtcScene = nullptr;
    std::vector<Geometry> geometries; // by Embree geometry id
    std::vector<LinearTexture> textures;
    float offsetScale = 1e-5f; // ray offsets relative to the scene's extent
    bool layered = true;       // Surfaces::Gltf

    void check(const char* what) const {
        const RTCError e = rtcGetDeviceError(device);
        if (e != RTC_ERROR_NONE)
            throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                                     std::to_string(int(e)) + ")");
    }
    ~Impl() {
        if (rtcScene) rtcReleaseScene(rtcScene);
        if (device) rtcReleaseDevice(device);
    }
};

const std::map<std::string, RayScene::Surfaces>& RayScene::surfaceNames() {
    static const std::map<std::string, Surfaces> names{{"gltf", Surfaces::Gltf},
                                                       {"lambertian", Surfaces::Lambertian}};
    return names;
}

RayScene::RayScene(const engine::Scene& scene, Surfaces surfaces) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.scene = &scene;
    m.layered = surfaces == Surfaces::Gltf;
    m.device = rtcNewDevice(nullptr);
    if (!m.device) throw std::runtime_error("Embree: cannot create a device");
    m.rtcScene = rtcNewScene(m.device);
    rtcSetSceneFlags(m.rtcScene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(m.rtcScene, RTC_BUILD_QUALITY_HIGH);
    m.check("scene creation");

    for (const engine::TextureImage& t : scene.textures)
        m.textures.push_back(t.width && t.height && t.rgba.size() >= size_t(t.width) * t.height * 4
                                 ? decode(t)
                                 : LinearTexture{});

    float extent = 1.0f;
    for (uint32_t i = 0; i < scene.instances.size(); ++i) {
        const engine::Instance& inst = scene.instances[i];
        const engine::Mesh& mesh = scene.meshes[inst.mesh];
        if (mesh.indexCount < 3) continue;
        Geometry g;
        g.instance = i;
        g.firstIndex = mesh.firstIndex;
        g.vertexOffset = mesh.vertexOffset;
        g.material = mesh.material;
        g.normalMatrix = glm::transpose(glm::inverse(glm::mat3(inst.transform)));
        const auto first = scene.indices.begin() + mesh.firstIndex;
        const auto last = first + (mesh.indexCount / 3) * 3;
        const auto [lo, hi] = std::minmax_element(first, last);
        g.minIndex = *lo;
        for (uint32_t v = *lo; v <= *hi; ++v) {
            const glm::vec3 p = glm::vec3(
                inst.transform * glm::vec4(scene.vertices[size_t(v + g.vertexOffset)].position, 1.0f));
            g.positions.push_back(p);
            extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        }
        const size_t triangles = size_t(last - first) / 3;
        RTCGeometry geom = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        // Embree's own buffers: it pads them for its SIMD loads.
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), g.positions.size()));
        auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
            geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), triangles));
        m.check("buffer allocation");
        for (size_t v = 0; v < g.positions.size(); ++v)
            for (int c = 0; c < 3; ++c)
                vb[v * 3 + size_t(c)] = g.positions[v][c];
        for (size_t k = 0; k < triangles * 3; ++k)
            ib[k] = first[std::ptrdiff_t(k)] - g.minIndex;
        rtcCommitGeometry(geom);
        const uint32_t id = rtcAttachGeometry(m.rtcScene, geom);
        rtcReleaseGeometry(geom);
        m.check("geometry");
        if (m.geometries.size() <= id) m.geometries.resize(id + 1);
        m.geometries[id] = std::move(g);
    }
    rtcCommitScene(m.rtcScene);
    m.check("BVH build");
    // Rays start this far off their surface: above float rounding of positions this far from the
    // origin, far below any feature of a scene in metres.
    m.offsetScale = 1e-5f * extent;
}

RayScene::~RayScene() = default;

std::optional<SurfacePoint> RayScene::intersect(glm::vec3 origin, glm::vec3 direction,
                                                float maxDistance) const {
    const Impl& m = *impl_;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = direction.x;
    rh.ray.dir_y = direction.y;
    rh.ray.dir_z = direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = maxDistance;
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m.rtcScene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    const Geometry& g = m.geometries[rh.hit.geomID];
    const engine::Scene& scene = *m.scene;
    uint32_t index[3];
    for (uint32_t k = 0; k < 3; ++k)
        index[k] = scene.indices[g.firstIndex + rh.hit.primID * 3 + k];
    const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
    const glm::vec3 p0 = g.positions[index[0] - g.minIndex], p1 = g.positions[index[1] - g.minIndex],
                    p2 = g.positions[index[2] - g.minIndex];
    const engine::Vertex& a = scene.vertices[size_t(index[0] + g.vertexOffset)];
    const engine::Vertex& b = scene.vertices[size_t(index[1] + g.vertexOffset)];
    const engine::Vertex& c = scene.vertices[size_t(index[2] + g.vertexOffset)];

    SurfacePoint s;
    s.instance = g.instance;
    // From the barycentrics on the triangle itself: closer to the plane than origin + t x direction.
    s.position = w * p0 + u * p1 + v * p2;
    glm::vec3 ng = glm::cross(p1 - p0, p2 - p0);
    const float ngLength = glm::length(ng);
    ng = ngLength > 0.0f ? ng / ngLength : -direction;
    if (glm::dot(ng, direction) > 0.0f) ng = -ng;
    glm::vec3 ns = g.normalMatrix * (w * a.normal + u * b.normal + v * c.normal);
    const float nsLength = glm::length(ns);
    ns = nsLength > 0.0f ? ns / nsLength : ng;
    // The shading normal on the side the ray came from, as the geometric one.
    if (glm::dot(ns, ng) < 0.0f) ns = -ns;
    s.geometricNormal = ng;
    s.normal = ns;

    const engine::Material* material =
        g.material < scene.materials.size() ? &scene.materials[g.material] : nullptr;
    if (!material) {
        s.albedo = glm::vec3(1.0f);
        s.layered = m.layered;
        s.f0 = m.layered ? glm::vec3(0.04f) : glm::vec3(0.0f);
        return s;
    }
    const glm::vec2 uv = w * a.uv + u * b.uv + v * c.uv;
    glm::vec3 base = glm::vec3(material->baseColor);
    const auto textured = [&](int32_t t) -> const LinearTexture* {
        return t >= 0 && size_t(t) < m.textures.size() && !m.textures[size_t(t)].texels.empty()
                   ? &m.textures[size_t(t)]
                   : nullptr;
    };
    if (const LinearTexture* t = textured(material->baseColorTexture)) base *= glm::vec3(t->sample(uv));
    float metallic = material->metallic;
    // glTF: metallic in B of the (linear) metallic-roughness map, as the engine's G-buffer reads it.
    if (const LinearTexture* t = textured(material->metallicRoughnessTexture)) metallic *= t->sample(uv).b;
    metallic = std::clamp(metallic, 0.0f, 1.0f);
    s.albedo = base * (1.0f - metallic);
    // The engine's lighting pass: F0 = mix(4%, base colour, metallic).
    s.layered = m.layered;
    s.f0 = m.layered ? glm::mix(glm::vec3(0.04f), base, metallic) : glm::vec3(0.0f);
    return s;
}

glm::vec3 SurfacePoint::diffuseShare(glm::vec3 toLight, glm::vec3 toViewer) const {
    if (!layered) return glm::vec3(1.0f);
    const glm::vec3 sum = toLight + toViewer;
    const float length = glm::length(sum);
    // Opposite directions have no half vector; toward them v.h goes to 0 and F to 1.
    const float vh = length > 1e-6f ? std::max(glm::dot(toViewer, sum / length), 0.0f) : 0.0f;
    const float weight = std::pow(1.0f - vh, 5.0f);
    return glm::vec3(1.0f) - (f0 + (glm::vec3(1.0f) - f0) * weight);
}

const engine::Bounds& RayScene::bounds() const {
    return impl_->scene->bounds;
}

glm::vec3 RayScene::rayOrigin(const SurfacePoint& from, glm::vec3 direction) const {
    const float side = glm::dot(direction, from.geometricNormal) >= 0.0f ? 1.0f : -1.0f;
    return from.position + side * impl_->offsetScale * from.geometricNormal;
}

bool RayScene::occluded(const SurfacePoint& from, glm::vec3 direction, float distance) const {
    return occluded(rayOrigin(from, direction), direction,
                    std::isinf(distance) ? distance : std::max(0.0f, distance - 2.0f * impl_->offsetScale));
}

bool RayScene::occluded(glm::vec3 origin, glm::vec3 direction, float distance) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = 0.0f;
    ray.tfar = distance;
    ray.mask = 0xffffffffu;
    rtcOccluded1(impl_->rtcScene, &context, &ray);
    return ray.tfar < 0.0f; // Embree sets -inf on a hit
}

} // namespace lpv::reference
