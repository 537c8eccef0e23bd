// The GL backend's barrier bits (rhi/gl/GlHazards.h), without a context: which glMemoryBarrier
// bits a command needs after earlier shader stores and reads, and what a barrier clears.
#include "GlHazards.h"

#include <doctest/doctest.h>

using lpv::rhi::gl::GlHazards;

namespace {
const uint64_t kImage = GlHazards::textureKey(7);
const uint64_t kOther = GlHazards::textureKey(8);
const uint64_t kBuffer = GlHazards::bufferKey(7); // the same GL name as kImage, another namespace
} // namespace

TEST_CASE("gl hazards: a read after a shader store pays the bit of that read, once") {
    GlHazards h;
    CHECK(h.beforeRead(kImage, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) == 0);
    REQUIRE(h.noteWrite(kImage));
    CHECK(h.beforeRead(kImage, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) == GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(h.beforeRead(kImage, GL_TEXTURE_FETCH_BARRIER_BIT) == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(h.beforeRead(kOther, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) == 0); // independent: no barrier
    CHECK(h.beforeRead(kBuffer, GL_SHADER_STORAGE_BARRIER_BIT) == 0);
    h.paid(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(h.beforeRead(kImage, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) == 0);
    // The barrier covered image loads only: sampling the image still needs its own bit.
    CHECK(h.beforeRead(kImage, GL_TEXTURE_FETCH_BARRIER_BIT) == GL_TEXTURE_FETCH_BARRIER_BIT);
    CHECK(h.beforeCommandWrite(kImage, GL_FRAMEBUFFER_BARRIER_BIT) == GL_FRAMEBUFFER_BARRIER_BIT);
    h.paid(GL_ALL_BARRIER_BITS);
    CHECK(h.empty());
    CHECK(h.beforeRead(kImage, GL_TEXTURE_FETCH_BARRIER_BIT) == 0);
}

TEST_CASE("gl hazards: a shader store waits for earlier stores and reads of the same resource") {
    GlHazards h;
    REQUIRE(h.noteRead(kImage, false)); // sampled by an earlier draw
    CHECK(h.beforeShaderWrite(kImage, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) ==
          GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(h.beforeShaderWrite(kOther, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) == 0);
    // A texture fetch is ordered with later GL commands: a clear of it needs nothing.
    CHECK(h.beforeCommandWrite(kImage, GL_TEXTURE_UPDATE_BARRIER_BIT) == 0);
    h.paid(GL_SHADER_STORAGE_BARRIER_BIT); // a buffer's store bit does not cover an image
    CHECK(h.beforeShaderWrite(kImage, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) != 0);
    h.paid(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    CHECK(h.beforeShaderWrite(kImage, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) == 0);

    REQUIRE(h.noteWrite(kBuffer));
    CHECK(h.beforeShaderWrite(kBuffer, GL_SHADER_STORAGE_BARRIER_BIT) == GL_SHADER_STORAGE_BARRIER_BIT);
    CHECK(h.beforeCommandWrite(kBuffer, GL_BUFFER_UPDATE_BARRIER_BIT) == GL_BUFFER_UPDATE_BARRIER_BIT);
}

TEST_CASE("gl hazards: a GL command writing what shaders loaded incoherently pays every bit") {
    GlHazards h;
    REQUIRE(h.noteRead(kImage, true)); // an image load
    CHECK(h.beforeCommandWrite(kImage, GL_TEXTURE_UPDATE_BARRIER_BIT) == GL_ALL_BARRIER_BITS);
    CHECK(h.beforeRead(kImage, GL_TEXTURE_FETCH_BARRIER_BIT) == 0); // read after read: nothing
}

TEST_CASE("gl hazards: a store after a barrier is visible again only after the next one") {
    GlHazards h;
    REQUIRE(h.noteWrite(kImage));
    h.paid(GL_ALL_BARRIER_BITS);
    REQUIRE(h.noteWrite(kImage));
    CHECK(h.beforeRead(kImage, GL_TEXTURE_FETCH_BARRIER_BIT) == GL_TEXTURE_FETCH_BARRIER_BIT);
}

TEST_CASE("gl hazards: a full list says so instead of forgetting a store") {
    GlHazards h;
    uint32_t noted = 0;
    while (h.noteWrite(GlHazards::textureKey(100 + noted)))
        ++noted;
    CHECK(noted > 8);
    CHECK(h.beforeRead(GlHazards::textureKey(100), GL_TEXTURE_FETCH_BARRIER_BIT) != 0);
    h.paid(GL_ALL_BARRIER_BITS);
    CHECK(h.noteWrite(GlHazards::textureKey(100 + noted)));
}
