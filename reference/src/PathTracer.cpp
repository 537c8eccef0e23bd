// The estimator: at the visible surface x0, direct = albedo / pi x E_direct(x0); the indirect
// irradiance is sampled with cosine-weighted directions (pdf cos / pi, so each path's weight is the
// product of the albedos met), with next-event estimation (DirectLighting) at every later vertex:
// E_indirect ~ sum over k = 1..bounces of (albedo_1 x ... x albedo_k) E_direct(x_k).
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
#include <mutex>
#include <thread>

namespace lpv::reference {
namespace {

constexpr float kPi = 3.14159265358979f;

// One path's estimate of the indirect irradiance at p (cosine-weighted, so no cosine or pdf
// factors remain: pi x albedo / pi per vertex).
// `first` is the first bounce's pair of uniforms (stratified by the caller).
glm::vec3 indirectSample(const RayScene& scene, const DirectLighting& lights, const SurfacePoint& p,
                         uint32_t bounces, glm::vec2 first, Random& random) {
    glm::vec3 sum(0.0f), weight(1.0f);
    SurfacePoint at = p;
    for (uint32_t k = 0; k < bounces; ++k) {
        const glm::vec2 u = k == 0 ? first : glm::vec2(random.uniform(), random.uniform());
        const glm::vec3 dir = cosineDirection(at.normal, u.x, u.y);
        // Below the triangle (a smooth normal tilted away from it): the surface itself is in the way.
        if (glm::dot(dir, at.geometricNormal) <= 0.0f) break;
        const std::optional<SurfacePoint> next = scene.intersect(scene.rayOrigin(at, dir), dir);
        if (!next) break; // black sky
        weight *= next->albedo;
        if (weight.x <= 0.0f && weight.y <= 0.0f && weight.z <= 0.0f) break;
        sum += weight * lights.irradiance(*next, scene);
        at = *next;
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
                             uint32_t bounces, uint32_t samples, uint64_t seed) {
    Random random(seed, 0);
    glm::vec3 sum(0.0f);
    for (uint32_t s = 0; s < samples; ++s)
        sum += indirectSample(scene, lights, p, bounces, stratified(s, samples, random), random);
    return samples ? sum / float(samples) : sum;
}

TracedImage trace(const RayScene& scene, const DirectLighting& lights, const engine::Camera& camera,
                  const TraceSettings& settings) {
    TracedImage image;
    image.width = settings.width;
    image.height = settings.height;
    const size_t count = size_t(settings.width) * settings.height;
    for (auto* v : {&image.indirect, &image.direct, &image.combined, &image.position, &image.normal})
        v->assign(count, glm::vec3(0.0f));
    image.hit.assign(count, 0);
    if (count == 0) return image;

    const glm::mat4 invViewProjection =
        engine::cameraMatrices(camera, float(settings.width) / float(settings.height)).invViewProjection;
    const uint32_t spp = std::max(1u, settings.samplesPerPixel);
    const uint32_t bounces = std::clamp(settings.bounces, 0u, 16u);

    std::atomic<uint32_t> nextRow{0}, rowsDone{0};
    std::mutex progressMutex;
    int shownPercent = -1;
    const auto renderRows = [&] {
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
                // The pixel's own stream: the same image from any number of threads.
                Random random(settings.seed, i);
                glm::vec3 direct(0.0f), indirect(0.0f);
                for (uint32_t s = 0; s < spp; ++s) {
                    const float jx = random.uniform(), jy = random.uniform();
                    const Ray ray = cameraRay(invViewProjection, float(x) + jx, float(y) + jy, settings.width,
                                              settings.height);
                    const std::optional<SurfacePoint> p = scene.intersect(ray.origin, ray.direction);
                    if (!p) continue;
                    const glm::vec3 diffuse = p->albedo / kPi;
                    direct += diffuse * lights.irradiance(*p, scene);
                    const glm::vec2 first = stratified(s, spp, random);
                    if (bounces > 0)
                        indirect += diffuse * indirectSample(scene, lights, *p, bounces, first, random);
                }
                image.direct[i] = direct / float(spp);
                image.indirect[i] = indirect / float(spp);
                image.combined[i] = image.direct[i] + image.indirect[i];
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
    return image;
}

TracedImage trace(const engine::Scene& scene, const engine::Camera& camera, const TraceSettings& settings) {
    const RayScene rays(scene);
    const SceneLights lights(scene);
    return trace(rays, lights, camera, settings);
}

} // namespace lpv::reference
