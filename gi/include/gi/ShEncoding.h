// How an rgba8 volume stores SH coefficients (gi.sh_format=rgba8): v in [-range, range] as the
// 8-bit code 128 + 127 v / range, the same as lpv_common.glsl's encodeShRange / decodeShRange.
// Zero is a code (128), so an empty cell reads back as no light (to float rounding): with the
// midpoint between two codes it decoded as +-range / 255, and the lookup's clamp of negative
// irradiance kept the positive half: light where there was none (with the old single range in
// intensity as well, the Cornell box's indirect light came out 31% too bright at range 2 and 87% at
// 4, PC settings, 640x360). The decode is affine in the code, so a sampler's filtering of the codes
// stays exact.
#pragma once

#include <glm/common.hpp>
#include <glm/vec4.hpp>

namespace lpv::gi {

// The stored value (the texel's normalized [0, 1] reading) for coefficients `v`.
inline glm::vec4 encodeShRange(const glm::vec4& v, float range) {
    return glm::clamp((v / range * 127.0f + 128.0f) / 255.0f, 0.0f, 1.0f);
}

// The coefficients a normalized texel reading `code` stands for.
inline glm::vec4 decodeShRange(const glm::vec4& code, float range) {
    return (code * 255.0f - 128.0f) / 127.0f * range;
}

} // namespace lpv::gi
