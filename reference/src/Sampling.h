// Random numbers and directions for the path tracer, the same on every platform and compiler (the
// std:: distributions are not): PCG32 streams seeded by a splitmix64 hash, floats from 24 bits.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lpv::reference {

inline uint64_t splitmix64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// PCG32 (O'Neill, pcg32_random_r): one stream per pixel, so the image does not depend on which
// thread renders which pixel.
class Random {
public:
    Random(uint64_t seed, uint64_t stream) {
        increment_ = (splitmix64(stream ^ 0x5851f42d4c957f2dull) << 1u) | 1u;
        state_ = 0;
        next();
        state_ += splitmix64(seed);
        next();
    }
    uint32_t next() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + increment_;
        const auto xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const auto rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    // Uniform in [0, 1).
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }

private:
    uint64_t state_ = 0, increment_ = 1;
};

// Two unit vectors that make an orthonormal basis with the unit n, without branches on n (Duff et
// al. 2017).
inline void orthonormalBasis(glm::vec3 n, glm::vec3& t, glm::vec3& bt) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    bt = glm::vec3(b, sign + n.y * n.y * a, -n.y);
}

// A cosine-weighted direction around the unit normal n (pdf = cos / pi).
inline glm::vec3 cosineDirection(glm::vec3 n, float u1, float u2) {
    glm::vec3 t, bt;
    orthonormalBasis(n, t, bt);
    const float r = std::sqrt(u1), phi = 6.28318530718f * u2;
    const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
    return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * bt + z * n);
}

} // namespace lpv::reference
