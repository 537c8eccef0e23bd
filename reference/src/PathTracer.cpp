// The estimator: at the visible surface x0, direct = albedo / pi x E_direct(x0); the indirect
// irradiance is sampled with cosine-weighted directions (pdf cos / pi, so each path's weight is the
// product of the albedos met), with next-event estimation (DirectLighting) at every later vertex:
// E_indirect ~ sum over k = 1..bounces of (albedo_1 x ... x albedo_k) E_direct(x_k). On glTF's
// layered surfaces each vertex also takes the share its diffuse base reflects from the direction
// the light arrives along toward the one it leaves along (SurfacePoint::diffuseShare).
// A medium adds, per camera ray, distances drawn in proportion to sigma_t x transmittance, so each
// carries the weight albedo x (1 - T(surface)) times the light scattered there: the sun's, shadowed,
// times the phase function, and the radiance of the surface met by a phase-sampled ray.
#include "reference/PathTracer.h"

#include "Sampling.h"

#include "engine/render/CameraMatrices.h"

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <thread>

namespace lpv::reference {
namespace {

constexpr float kPi = 3.14159265358979f;

// One path's estimate of the indirect irradiance at p that its diffuse base reflects toward
// `toViewer` (cosine-weighted, so no cosine or pdf factors remain: pi x albedo / pi per vertex).
// `first` is the first bounce's pair of uniforms (stratified by the caller).
glm::vec3 indirectSample(const RayScene& scene, const DirectLighting& lights, const SurfacePoint& p,
                         glm::vec3 toViewer, uint32_t bounces, glm::vec2 first, Random& random) {
    glm::vec3 sum(0.0f), weight(1.0f);
    SurfacePoint at = p;
    glm::vec3 out = toViewer;
    for (uint32_t k = 0; k < bounces; ++k) {
        const glm::vec2 u = k == 0 ? first : glm::vec2(random.uniform(), random.uniform());
        const glm::vec3 dir = cosineDirection(at.normal, u.x, u.y);
        // Below the triangle (a smooth normal tilted away from it): the surface itself is in the way.
        if (glm::dot(dir, at.geometricNormal) <= 0.0f) break;
        const std::optional<SurfacePoint> next = scene.intersect(scene.rayOrigin(at, dir), dir);
        if (!next) break; // black sky
        weight *= at.diffuseShare(dir, out) * next->albedo;
        if (weight.x <= 0.0f && weight.y <= 0.0f && weight.z <= 0.0f) break;
        sum += weight * lights.irradiance(*next, scene, -dir);
        at = *next;
        out = -dir;
    }
    return sum;
}

// The first bounce's uniforms for sample s of `count`: the first n x n samples (n = floor(sqrt(count)))
// fall one in each cell of a jittered n x n grid, the rest anywhere. Stratifying the directions from
// a surface cuts the noise where light comes from a small bright patch (a sunlit spot seen through
// the room); the pixel jitter stays independent, so the cells (pixel x direction cell) tile the
// domain and the mean stays unbiased.
glm::vec2 stratified(uint32_t s, uint32_t count, Random& random) {
    const auto n = uint32_t(std::sqrt(double(count)));
    const float r1 = random.uniform(), r2 = random.uniform();
    if (s >= n * n) return {r1, r2};
    return {(float(s % n) + r1) / float(n), (float(s / n) + r2) / float(n)};
}

struct Ray {
    glm::vec3 origin, direction;
};

// How far a camera ray that meets no surface goes through the medium (Medium::missAtSceneBounds).
float missDistance(const RayScene& scene, const Medium& medium, glm::vec3 origin, glm::vec3 direction) {
    if (!medium.missAtSceneBounds) return medium.missDistance;
    const engine::Bounds& box = scene.bounds();
    if (box.empty()) return 0.0f;
    float near = 0.0f, far = std::numeric_limits<float>::infinity();
    for (int c = 0; c < 3; ++c) {
        if (direction[c] == 0.0f) {
            if (origin[c] < box.min[c] || origin[c] > box.max[c]) return 0.0f;
            continue;
        }
        const float a = (box.min[c] - origin[c]) / direction[c], b = (box.max[c] - origin[c]) / direction[c];
        near = std::max(near, std::min(a, b));
        far = std::min(far, std::max(a, b));
    }
    return far >= near ? far : 0.0f;
}

struct InScatter {
    glm::vec3 sun{0.0f}, indirect{0.0f};
};

// The medium samples of one pixel: `passes` camera samples of `count` each. Sample m of pass p has
// index k = m x passes + p of count x passes: it takes the k-th stratum of the distance distribution
// and the order[k]-th cell of the directions (stratified() over as many), so both spread evenly
// over the pixel; the order is a random permutation, which keeps each sample's direction cell
// independent of its distance and the estimate unbiased.
struct MediumStrata {
    uint32_t count = 0, pass = 0, passes = 1;
    std::span<const uint32_t> order;
};

// A uniformly random permutation of 0..n-1 (Fisher-Yates).
void shuffle(std::vector<uint32_t>& order, uint32_t n, Random& random) {
    order.resize(n);
    for (uint32_t i = 0; i < n; ++i)
        order[i] = i;
    for (uint32_t i = n; i > 1; --i)
        std::swap(order[i - 1], order[uint32_t((uint64_t(random.next()) * i) >> 32)]);
}

// The mean of strata.count estimates of the light the medium scatters toward `origin` from the
// segment origin + [0, distance] x direction, before the transmittance from the camera (which the
// distance sampling folds in).
InScatter inScatter(const RayScene& scene, const DirectLighting& lights, const std::optional<Sun>& sun,
                    const Medium& medium, glm::vec3 origin, glm::vec3 direction, float distance,
                    uint32_t bounces, const MediumStrata& strata, Random& random) {
    InScatter sum;
    const float opacity = 1.0f - transmittance(medium, origin, direction, distance);
    if (!(opacity > 0.0f) || strata.count == 0) return sum;
    const float sunPhase =
        sun ? henyeyGreenstein(glm::dot(sun->direction, -direction), medium.anisotropy) : 0.0f;
    const uint32_t total = strata.count * strata.passes;
    for (uint32_t m = 0; m < strata.count; ++m) {
        const uint32_t k = m * strata.passes + strata.pass;
        const float u = (float(k) + random.uniform()) / float(total);
        const glm::vec3 x = origin + sampleDistance(medium, origin, direction, distance, u) * direction;
        if (sunPhase > 0.0f && !scene.occluded(x, -sun->direction)) {
            const float toSun =
                medium.attenuateSunlight
                    ? transmittance(medium, x, -sun->direction, std::numeric_limits<double>::infinity())
                    : 1.0f;
            sum.sun += sun->irradiance * (sunPhase * toSun);
        }
        if (bounces == 0) continue;
        // Where the light that leaves toward the camera came from: the phase function is symmetric,
        // so a direction drawn around the outgoing one serves as the incident one.
        const glm::vec2 cell = stratified(strata.order[k], total, random);
        const glm::vec3 incident = sampleHenyeyGreenstein(-direction, medium.anisotropy, cell.x, cell.y);
        const std::optional<SurfacePoint> q = scene.intersect(x, -incident);
        if (!q) continue;
        glm::vec3 e = lights.irradiance(*q, scene, incident);
        if (bounces > 1) {
            const float v1 = random.uniform(), v2 = random.uniform();
            e += indirectSample(scene, lights, *q, incident, bounces - 1, {v1, v2}, random);
        }
        sum.indirect += q->albedo / kPi * e;
    }
    const glm::vec3 weight = medium.albedo * (opacity / float(strata.count));
    sum.sun *= weight;
    sum.indirect *= weight;
    return sum;
}

Ray cameraRay(const glm::mat4& invViewProjection, float x, float y, uint32_t width, uint32_t height) {
    // Row 0 at the top is NDC y = -1 (the projection's y is flipped); depth 0 is the near plane.
    const float nx = 2.0f * x / float(width) - 1.0f, ny = 2.0f * y / float(height) - 1.0f;
    const glm::vec4 nearPoint = invViewProjection * glm::vec4(nx, ny, 0.0f, 1.0f);
    const glm::vec4 farPoint = invViewProjection * glm::vec4(nx, ny, 1.0f, 1.0f);
    const glm::vec3 a = glm::vec3(nearPoint) / nearPoint.w, b = glm::vec3(farPoint) / farPoint.w;
    return {a, glm::normalize(b - a)};
}

} // namespace

glm::vec3 indirectIrradiance(const RayScene& scene, const DirectLighting& lights, const SurfacePoint& p,
                             glm::vec3 toViewer, uint32_t bounces, uint32_t samples, uint64_t seed) {
    Random random(seed, 0);
    glm::vec3 sum(0.0f);
    for (uint32_t s = 0; s < samples; ++s)
        sum += indirectSample(scene, lights, p, toViewer, bounces, stratified(s, samples, random), random);
    return samples ? sum / float(samples) : sum;
}

MediumRadiance scatteredAlongRay(const RayScene& scene, const DirectLighting& lights, const Medium& medium,
                                 glm::vec3 origin, glm::vec3 direction, uint32_t bounces, uint32_t samples,
                                 uint64_t seed) {
    MediumRadiance r;
    const std::optional<SurfacePoint> hit = scene.intersect(origin, direction);
    r.distance = hit ? glm::length(hit->position - origin) : missDistance(scene, medium, origin, direction);
    if (!medium.present()) return r;
    r.transmittance = transmittance(medium, origin, direction, r.distance);
    Random random(seed, 0);
    std::vector<uint32_t> order;
    shuffle(order, samples, random);
    const InScatter f = inScatter(scene, lights, lights.sun(), medium, origin, direction, r.distance, bounces,
                                  {samples, 0, 1, order}, random);
    r.sun = f.sun;
    r.indirect = f.indirect;
    return r;
}

TracedImage trace(const RayScene& scene, const DirectLighting& lights, const engine::Camera& camera,
                  const TraceSettings& settings) {
    TracedImage image;
    image.width = settings.width;
    image.height = settings.height;
    const size_t count = size_t(settings.width) * settings.height;
    for (auto* v : {&image.indirect, &image.direct, &image.combined, &image.position, &image.normal,
                    &image.fogSun, &image.fogIndirect, &image.fog, &image.fogged})
        v->assign(count, glm::vec3(0.0f));
    image.transmittance.assign(count, glm::vec3(1.0f));
    image.hit.assign(count, 0);
    if (count == 0) return image;

    const glm::mat4 invViewProjection =
        engine::cameraMatrices(camera, float(settings.width) / float(settings.height)).invViewProjection;
    const uint32_t spp = std::max(1u, settings.samplesPerPixel);
    const uint32_t bounces = std::clamp(settings.bounces, 0u, 16u);
    const Medium& medium = settings.medium;
    const bool fog = medium.present();
    const std::optional<Sun> sun = lights.sun();

    std::atomic<uint32_t> nextRow{0}, rowsDone{0};
    std::mutex progressMutex;
    int shownPercent = -1;
    const auto renderRows = [&] {
        std::vector<uint32_t> order; // the pixel's direction cells (MediumStrata)
        for (uint32_t y; (y = nextRow.fetch_add(1)) < settings.height;) {
            for (uint32_t x = 0; x < settings.width; ++x) {
                const size_t i = size_t(y) * settings.width + x;
                const Ray centre = cameraRay(invViewProjection, float(x) + 0.5f, float(y) + 0.5f,
                                             settings.width, settings.height);
                if (const std::optional<SurfacePoint> s = scene.intersect(centre.origin, centre.direction)) {
                    image.hit[i] = 1;
                    image.position[i] = s->position;
                    image.normal[i] = s->normal;
                }
                // The pixel's own stream: the same image from any number of threads. The medium has
                // another, so that it leaves the surfaces' images as they were.
                Random random(settings.seed, i);
                Random mediumRandom(settings.seed, i | (uint64_t(1) << 63));
                if (fog) shuffle(order, settings.mediumSamples * spp, mediumRandom);
                glm::vec3 direct(0.0f), indirect(0.0f), fogSun(0.0f), fogIndirect(0.0f), fogged(0.0f);
                float transmittance = 0.0f;
                for (uint32_t s = 0; s < spp; ++s) {
                    const float jx = random.uniform(), jy = random.uniform();
                    const Ray ray = cameraRay(invViewProjection, float(x) + jx, float(y) + jy, settings.width,
                                              settings.height);
                    const std::optional<SurfacePoint> p = scene.intersect(ray.origin, ray.direction);
                    glm::vec3 surface(0.0f);
                    if (p) {
                        const glm::vec3 diffuse = p->albedo / kPi;
                        const glm::vec3 d = diffuse * lights.irradiance(*p, scene, -ray.direction);
                        direct += d;
                        surface = d;
                        const glm::vec2 first = stratified(s, spp, random);
                        if (bounces > 0) {
                            const glm::vec3 b = diffuse * indirectSample(scene, lights, *p, -ray.direction,
                                                                         bounces, first, random);
                            indirect += b;
                            surface += b;
                        }
                    }
                    if (!fog) continue;
                    // From the eye, which the ray from the near plane passes through.
                    const float distance = p ? glm::length(p->position - camera.position)
                                             : missDistance(scene, medium, camera.position, ray.direction);
                    const float t =
                        reference::transmittance(medium, camera.position, ray.direction, distance);
                    const InScatter f =
                        inScatter(scene, lights, sun, medium, camera.position, ray.direction, distance,
                                  bounces, {settings.mediumSamples, s, spp, order}, mediumRandom);
                    transmittance += t;
                    fogSun += f.sun;
                    fogIndirect += f.indirect;
                    fogged += surface * t + f.sun + f.indirect;
                }
                image.direct[i] = direct / float(spp);
                image.indirect[i] = indirect / float(spp);
                image.combined[i] = image.direct[i] + image.indirect[i];
                if (fog) {
                    image.fogSun[i] = fogSun / float(spp);
                    image.fogIndirect[i] = fogIndirect / float(spp);
                    image.fog[i] = image.fogSun[i] + image.fogIndirect[i];
                    image.transmittance[i] = glm::vec3(transmittance / float(spp));
                    image.fogged[i] = fogged / float(spp);
                }
            }
            const uint32_t done = rowsDone.fetch_add(1) + 1;
            if (settings.progress) {
                const int percent = int(uint64_t(done) * 100 / settings.height);
                const std::lock_guard lock(progressMutex);
                if (percent != shownPercent) {
                    shownPercent = percent;
                    std::fprintf(stderr, "\rlpv_reference: %3d%% (%u of %u rows)", percent, done,
                                 settings.height);
                    std::fflush(stderr);
                }
            }
        }
    };
    uint32_t threads =
        settings.threads ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    threads = std::min(threads, settings.height);
    std::vector<std::thread> pool;
    for (uint32_t t = 1; t < threads; ++t)
        pool.emplace_back(renderRows);
    renderRows();
    for (std::thread& t : pool)
        t.join();
    if (settings.progress) std::fprintf(stderr, "\n");
    if (!fog) image.fogged = image.combined;
    return image;
}

TracedImage trace(const engine::Scene& scene, const engine::Camera& camera, const TraceSettings& settings) {
    const RayScene rays(scene, settings.surfaces);
    const SceneLights lights(scene);
    return trace(rays, lights, camera, settings);
}

} // namespace lpv::reference
