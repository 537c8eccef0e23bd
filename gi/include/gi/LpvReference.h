// The CPU reference of injection and propagation: plain C++, straight from the papers, used by
// the tests to check the GPU volumes (never in a frame).
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace lpv::gi {

// One cell: SH intensity coefficients per colour channel.
struct ShCell {
    glm::vec4 r{0.0f}, g{0.0f}, b{0.0f};
};

struct VolumeGrid {
    glm::vec3 origin{0.0f}; // corner of cell (0,0,0)
    float cellSize = 1.0f;
    uint32_t size = 32; // cells per axis
};

class ShVolume {
public:
    explicit ShVolume(uint32_t size) : size_(size), cells_(size_t(size) * size * size) {}
    uint32_t size() const { return size_; }
    ShCell& at(uint32_t x, uint32_t y, uint32_t z) { return cells_[index(x, y, z)]; }
    const ShCell& at(uint32_t x, uint32_t y, uint32_t z) const { return cells_[index(x, y, z)]; }
    const std::vector<ShCell>& cells() const { return cells_; }
    std::vector<ShCell>& cells() { return cells_; }
    // Sum over cells of the L0 coefficient per channel: proportional to the total emitted flux
    // (an intensity with L0 coefficient c emits 4 pi Y00 c = 2 sqrt(pi) c watts).
    glm::vec3 totalL0() const;

private:
    size_t index(uint32_t x, uint32_t y, uint32_t z) const { return (size_t(z) * size_ + y) * size_ + x; }
    uint32_t size_;
    std::vector<ShCell> cells_;
};

// A virtual point light: a surfel of the reflective shadow map.
struct Vpl {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec3 flux{0.0f}; // watts per channel leaving the surfel
};

// The cell a VPL lands in after the half-cell shifts along its normal and toward the light
// (`lightDirection` is where the light travels); false when outside the volume.
bool injectionCell(const VolumeGrid& grid, const Vpl& vpl, glm::vec3 lightDirection, glm::ivec3& cell);

// Adds each VPL as a clamped-cosine lobe of intensity flux / pi around its normal.
void injectReference(ShVolume& volume, const VolumeGrid& grid, const std::vector<Vpl>& vpls,
                     glm::vec3 lightDirection);

// What lies beyond a volume's border, by cell (a coarser cascade's light, in this volume's units).
using ShBorder = std::function<ShCell(glm::ivec3)>;

// One propagation step: every cell gathers from its 6 neighbours through 5 faces each; neighbours
// beyond the volume hold `outside` (nothing when empty).
ShVolume propagateStep(const ShVolume& source, const ShBorder& outside = {});

// `iterations` steps, each propagating the previous step's result (never the initial volume),
// all accumulated onto the injected volume. `perIteration`, if given, receives each step's L0 total.
ShVolume propagateReference(const ShVolume& injected, int iterations,
                            std::vector<glm::vec3>* perIteration = nullptr);
// The shipped kernel's form with light from beyond the border (a cascade handoff): y(0) = x,
// y(k+1) = x + P(y(k), outside), the border holding `outside` at every step. With nothing outside
// it equals propagateReference.
ShVolume propagateWithBorder(const ShVolume& injected, int iterations, const ShBorder& outside);

} // namespace lpv::gi
