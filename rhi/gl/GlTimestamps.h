// GPU timing for the GL backend, one set of slots per frame, framesInFlight + 1 sets in a ring so
// a frame's results stay readable while later frames run.
//
// Where the time comes from: GL_TIME_ELAPSED and GL_TIMESTAMP read 0 or garbage on Mesa's software
// rasterizers (llvmpipe, softpipe; see ../shared/docs/lpv-notes.md). There the source is
// TimestampSource::CpuFinished: write() runs glFinish() and reads the CPU's steady clock, so the
// figure is "all GPU work recorded so far is done", at the cost of serializing the GPU. Results are
// readable once the frame has ended. Everywhere else the source is GpuQueries: glQueryCounter
// (GL_TIMESTAMP) per slot, read only when GL_QUERY_RESULT_AVAILABLE says so - read() never waits.
#pragma once

#include "GlFunctions.h"

#include "rhi/Device.h"

#include <cstdint>
#include <span>
#include <vector>

namespace lpv::rhi::gl {

class GlTimestamps {
public:
    // True when the renderer string names a software rasterizer with unusable timer queries.
    static TimestampSource sourceFor(std::string_view renderer);

    void create(const Functions& gl, TimestampSource source, uint32_t perFrame, uint32_t sets);
    void destroy();

    void beginFrame(uint64_t frame);
    void write(uint64_t frame, uint32_t slot);
    void endFrame(uint64_t frame);
    // Fills nanoseconds (0 for slots not written) and returns true when every written slot of
    // `frame` is available; false, without waiting, when not yet or no longer kept.
    bool read(uint64_t frame, std::span<uint64_t> out);

private:
    struct Set {
        uint64_t frame = 0;
        bool ended = false;
        std::vector<uint8_t> written;
        std::vector<uint64_t> cpuNs; // CpuFinished
        std::vector<GLuint> queries; // GpuQueries
    };
    Set& setFor(uint64_t frame) { return sets_[frame % sets_.size()]; }

    const Functions* gl_ = nullptr;
    TimestampSource source_ = TimestampSource::None;
    uint32_t perFrame_ = 0;
    std::vector<Set> sets_;
};

} // namespace lpv::rhi::gl
