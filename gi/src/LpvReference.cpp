// CPU reference of LPV injection and propagation.
#include "gi/LpvReference.h"

#include "gi/PropagationScheme.h"
#include "gi/ShBasis.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace lpv::gi {

glm::vec3 ShVolume::totalL0() const {
    glm::dvec3 sum(0.0);
    for (const ShCell& c : cells_)
        sum += glm::dvec3(c.r.x, c.g.x, c.b.x);
    return glm::vec3(sum);
}

bool injectionCell(const VolumeGrid& grid, const Vpl& vpl, glm::vec3 lightDirection, glm::ivec3& cell) {
    // Half a cell along the normal keeps a surfel out of the cell behind its own surface; half a
    // cell toward the light keeps it out of cells the light has not reached.
    const glm::vec3 p = vpl.position + 0.5f * grid.cellSize * (vpl.normal - lightDirection);
    const glm::vec3 c = glm::floor((p - grid.origin) / grid.cellSize);
    cell = glm::ivec3(c);
    return glm::all(glm::greaterThanEqual(cell, glm::ivec3(0))) &&
           glm::all(glm::lessThan(cell, glm::ivec3(int(grid.size))));
}

void injectReference(ShVolume& volume, const VolumeGrid& grid, const std::vector<Vpl>& vpls,
                     glm::vec3 lightDirection) {
    for (const Vpl& vpl : vpls) {
        glm::ivec3 c;
        if (!injectionCell(grid, vpl, lightDirection, c)) continue;
        const glm::vec4 lobe = shCosineLobe(vpl.normal) / kPi;
        ShCell& cell = volume.at(uint32_t(c.x), uint32_t(c.y), uint32_t(c.z));
        cell.r += lobe * vpl.flux.r;
        cell.g += lobe * vpl.flux.g;
        cell.b += lobe * vpl.flux.b;
    }
}

ShVolume propagateStep(const ShVolume& src, const ShBorder& outside) {
    const int n = int(src.size());
    ShVolume dst(src.size());
    std::array<std::array<PropagationFace, 5>, 6> faces;
    std::array<std::array<glm::vec4, 5>, 6> lobes;
    for (int a = 0; a < 6; ++a) {
        faces[size_t(a)] = propagationFaces(a);
        for (int f = 0; f < 5; ++f)
            lobes[size_t(a)][size_t(f)] = shCosineLobe(faces[size_t(a)][size_t(f)].normal);
    }
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                ShCell& out = dst.at(uint32_t(x), uint32_t(y), uint32_t(z));
                for (int a = 0; a < 6; ++a) {
                    // The neighbour sits on the opposite side of the axis it sends along.
                    const glm::ivec3 nb = glm::ivec3(x, y, z) - kAxes[size_t(a)];
                    const bool beyond = glm::any(glm::lessThan(nb, glm::ivec3(0))) ||
                                        glm::any(glm::greaterThanEqual(nb, glm::ivec3(n)));
                    if (beyond && !outside) continue;
                    const ShCell in =
                        beyond ? outside(nb) : src.at(uint32_t(nb.x), uint32_t(nb.y), uint32_t(nb.z));
                    for (int f = 0; f < 5; ++f) {
                        const PropagationFace& face = faces[size_t(a)][size_t(f)];
                        const glm::vec4 basis = shBasis(face.evalDirection);
                        // Flux through the face, re-emitted as a cosine lobe of intensity flux / pi.
                        // Not clamped at zero: the negative part of an L1 lobe travels too, which
                        // keeps the step linear and energy-conserving (PropagationScheme.h).
                        const float w = face.solidAngle / kPi;
                        const glm::vec4& lobe = lobes[size_t(a)][size_t(f)];
                        out.r += lobe * (w * glm::dot(in.r, basis));
                        out.g += lobe * (w * glm::dot(in.g, basis));
                        out.b += lobe * (w * glm::dot(in.b, basis));
                    }
                }
            }
    return dst;
}

ShVolume propagateReference(const ShVolume& injected, int iterations, std::vector<glm::vec3>* perIteration) {
    ShVolume accumulated = injected;
    ShVolume current = injected;
    for (int i = 0; i < iterations; ++i) {
        current = propagateStep(current);
        if (perIteration) perIteration->push_back(current.totalL0());
        for (size_t c = 0; c < current.cells().size(); ++c) {
            accumulated.cells()[c].r += current.cells()[c].r;
            accumulated.cells()[c].g += current.cells()[c].g;
            accumulated.cells()[c].b += current.cells()[c].b;
        }
    }
    return accumulated;
}

ShVolume propagateWithBorder(const ShVolume& injected, int iterations, const ShBorder& outside) {
    ShVolume y = injected;
    for (int i = 0; i < iterations; ++i) {
        ShVolume next = propagateStep(y, outside);
        for (size_t c = 0; c < next.cells().size(); ++c) {
            next.cells()[c].r += injected.cells()[c].r;
            next.cells()[c].g += injected.cells()[c].g;
            next.cells()[c].b += injected.cells()[c].b;
        }
        y = std::move(next);
    }
    return y;
}

} // namespace lpv::gi
