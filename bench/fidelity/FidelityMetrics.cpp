// The fidelity figures (FidelityMetrics.h).
#include "FidelityMetrics.h"

#include <cmath>
#include <stdexcept>

namespace lpv::bench {

namespace {

float luminance(glm::vec3 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

float ratioOf(double engine, double reference) {
    return reference > 0.0 ? float(engine / reference) : -1.0f;
}

} // namespace

FidelityFigures compareIndirect(std::span<const glm::vec3> engine, std::span<const glm::vec3> reference,
                                const ReferenceSurfaces& surfaces) {
    if (engine.size() != reference.size() || surfaces.normal.size() != reference.size() ||
        surfaces.hit.size() != reference.size())
        throw std::invalid_argument("compareIndirect: the images differ in size");
    FidelityFigures f;
    glm::dvec3 sumEngine(0.0), sumReference(0.0);
    double sumRefLum = 0.0, sumEngRef = 0.0, sumEngSq = 0.0, sumRefSq = 0.0;
    double orientEngine[3] = {}, orientReference[3] = {};
    for (size_t i = 0; i < reference.size(); ++i) {
        if (!surfaces.hit[i]) continue;
        const glm::vec3 e = engine[i], r = reference[i];
        ++f.pixels;
        sumEngine += glm::dvec3(e);
        sumReference += glm::dvec3(r);
        const double le = luminance(e), lr = luminance(r);
        sumRefLum += lr;
        sumEngRef += le * lr;
        sumEngSq += le * le;
        sumRefSq += lr * lr;
        const float ny = surfaces.normal[i].y;
        const int k = ny < -0.7f ? 0 : ny > 0.7f ? 1 : 2;
        orientEngine[k] += le;
        orientReference[k] += lr;
    }
    if (f.pixels == 0 || sumRefLum <= 0.0) return f;
    const double n = f.pixels, meanRef = sumRefLum / n;
    f.referenceMean = float(meanRef);
    f.meanRatio = glm::vec3(ratioOf(sumEngine.r, sumReference.r), ratioOf(sumEngine.g, sumReference.g),
                            ratioOf(sumEngine.b, sumReference.b));
    // sum (s e - r)^2 = s^2 sum e^2 - 2 s sum e r + sum r^2, least at s = sum e r / sum e^2.
    const auto rmseAt = [&](double s) {
        return std::sqrt(std::max(0.0, (s * s * sumEngSq - 2.0 * s * sumEngRef + sumRefSq) / n)) / meanRef;
    };
    f.relativeRmse = float(rmseAt(1.0));
    f.bestScale = sumEngSq > 0.0 ? float(sumEngRef / sumEngSq) : 1.0f;
    f.relativeRmseScaled = float(rmseAt(f.bestScale));
    f.orientation = {ratioOf(orientEngine[0], orientReference[0]),
                     ratioOf(orientEngine[1], orientReference[1]),
                     ratioOf(orientEngine[2], orientReference[2])};
    uint32_t over = 0;
    for (size_t i = 0; i < reference.size(); ++i) {
        if (!surfaces.hit[i]) continue;
        const double le = luminance(engine[i]), lr = luminance(reference[i]);
        if (le > 3.0 * lr && le > 0.01 * meanRef) ++over;
    }
    f.shareOver3x = float(over) / float(f.pixels);
    return f;
}

} // namespace lpv::bench
