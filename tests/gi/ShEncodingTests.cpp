// The rgba8 volumes' encoding (gi/ShEncoding.h, the same as lpv_common.glsl's).
#include "gi/ShEncoding.h"

#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

using namespace lpv;

TEST_CASE("gi: an rgba8 code for zero decodes to zero, and the decode is affine in the code") {
    // The lookup clamps negative irradiance, so an empty cell that decoded to a small positive or
    // negative value would turn into light where there is none. The midpoint encoding gave
    // +-range / 255; code 128 gives zero to float rounding (the texel's reading 128 / 255 is not
    // exact in float: a millionth of the range at most, whether or not the compiler fuses the decode).
    for (const float range : {0.5f, 12.0f, 300.0f}) {
        const glm::vec4 zero = gi::encodeShRange(glm::vec4(0.0f), range);
        CHECK(zero.x * 255.0f == doctest::Approx(128.0f));
        CHECK(std::fabs(gi::decodeShRange(glm::vec4(128.0f / 255.0f), range).x) <= 1e-6f * range);
        CHECK(gi::decodeShRange(glm::vec4(1.0f), range).x == doctest::Approx(range));
        // Half-way between two codes decodes half-way between their values (filtering is exact).
        const float a = gi::decodeShRange(glm::vec4(100.0f / 255.0f), range).x;
        const float b = gi::decodeShRange(glm::vec4(101.0f / 255.0f), range).x;
        CHECK(gi::decodeShRange(glm::vec4(100.5f / 255.0f), range).x == doctest::Approx(0.5f * (a + b)));
    }
}
