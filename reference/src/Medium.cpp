// The medium's closed forms. Along a ray x(t) = o + t w the height fog is constant where y lies
// at or below the base height and falls as exp(-a t), a = heightFalloff x w.y, above it: at most two
// pieces, split where the ray crosses the base plane. A piece starting at sigma_t = s has optical
// depth s (1 - exp(-a t)) / a (s t when a = 0), which inverts in closed form too. Doubles, and
// expm1/log1p, keep thin and nearly level media exact.
#include "reference/Medium.h"

#include "Sampling.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lpv::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The optical depth over `length` of a piece that starts at sigma_t = `start` and falls at `rate`.
double pieceDepth(double start, double rate, double length) {
    double integral; // of exp(-rate t) over [0, length]
    if (rate == 0.0 || length == 0.0)
        integral = length;
    else if (std::isinf(length))
        integral = rate > 0.0 ? 1.0 / rate : length;
    else
        integral = -std::expm1(-rate * length) / rate;
    if (std::isinf(integral)) return integral; // into ever denser (or endless) fog
    return start * integral;
}

// Its inverse: the length over which the piece reaches optical depth `depth`.
double pieceLength(double start, double rate, double depth) {
    const double integral = depth / start;
    return rate == 0.0 ? integral : -std::log1p(-rate * integral) / rate;
}

// sigma_t along a ray: the first piece over [0, split] (split may be infinite), the second after.
struct RayProfile {
    double start1 = 0.0, rate1 = 0.0, split = std::numeric_limits<double>::infinity();
    double start2 = 0.0, rate2 = 0.0;
};

RayProfile profile(const Medium& medium, glm::vec3 origin, glm::vec3 direction) {
    const double k = medium.heightFalloff, density = medium.density;
    const double above = double(origin.y) - double(medium.baseHeight), wy = double(direction.y);
    RayProfile r;
    if (k == 0.0) {
        r.start1 = density;
        return r;
    }
    const double crossing = wy != 0.0 ? -above / wy : std::numeric_limits<double>::infinity();
    if (above <= 0.0) {
        // In the constant layer; rising, the ray leaves it at the base plane.
        r.start1 = density;
        if (wy > 0.0) {
            r.split = crossing;
            r.start2 = density;
            r.rate2 = k * wy;
        }
        return r;
    }
    r.start1 = density * std::exp(-k * above);
    r.rate1 = k * wy;
    if (wy < 0.0) { // sinking, it enters the constant layer at the base plane
        r.split = crossing;
        r.start2 = density;
    }
    return r;
}

} // namespace

float henyeyGreenstein(float cosTheta, float g) {
    const double gg = double(g), d = 1.0 + gg * gg - 2.0 * gg * double(cosTheta);
    return float((1.0 - gg * gg) / (4.0 * kPi * d * std::sqrt(d)));
}

glm::vec3 sampleHenyeyGreenstein(glm::vec3 incident, float g, float u1, float u2) {
    // The inverse of the cosine's distribution function; uniform where g is too small for it to be
    // computed without cancellation.
    const double gg = double(g);
    double cosTheta = 1.0 - 2.0 * double(u1);
    if (std::abs(gg) > 1e-6) {
        const double s = (1.0 - gg * gg) / (1.0 - gg + 2.0 * gg * double(u1));
        cosTheta = (1.0 + gg * gg - s * s) / (2.0 * gg);
    }
    cosTheta = std::clamp(cosTheta, -1.0, 1.0);
    const auto sinTheta = float(std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta)));
    const float phi = 6.28318530718f * u2;
    glm::vec3 t, b;
    orthonormalBasis(incident, t, b);
    return glm::normalize(sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b +
                          float(cosTheta) * incident);
}

float extinction(const Medium& medium, glm::vec3 position) {
    if (!medium.present()) return 0.0f;
    const double above = std::max(double(position.y) - double(medium.baseHeight), 0.0);
    return float(double(medium.density) * std::exp(-double(medium.heightFalloff) * above));
}

double opticalDepth(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double distance) {
    if (!medium.present() || !(distance > 0.0)) return 0.0;
    const RayProfile r = profile(medium, origin, direction);
    if (distance <= r.split) return pieceDepth(r.start1, r.rate1, distance);
    return pieceDepth(r.start1, r.rate1, r.split) + pieceDepth(r.start2, r.rate2, distance - r.split);
}

float transmittance(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double distance) {
    return float(std::exp(-opticalDepth(medium, origin, direction, distance)));
}

float sampleDistance(const Medium& medium, glm::vec3 origin, glm::vec3 direction, double maxDistance,
                     float u) {
    const double opacity = -std::expm1(-opticalDepth(medium, origin, direction, maxDistance));
    const double depth = -std::log1p(-double(u) * opacity); // 1 - exp(-depth) = u x opacity
    const RayProfile r = profile(medium, origin, direction);
    const double firstDepth = pieceDepth(r.start1, r.rate1, r.split);
    const double t = depth <= firstDepth ? pieceLength(r.start1, r.rate1, depth)
                                         : r.split + pieceLength(r.start2, r.rate2, depth - firstDepth);
    // Only a sigma_t that underflows at the origin (absurdly far above the base) leaves t undefined.
    if (!std::isfinite(t)) return std::isfinite(maxDistance) ? float(maxDistance) : 0.0f;
    return float(std::clamp(t, 0.0, maxDistance));
}

} // namespace lpv::reference
