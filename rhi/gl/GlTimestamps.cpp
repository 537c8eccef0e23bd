// Timestamp ring of the GL backend; the choice of clock is explained in GlTimestamps.h.
#include "GlTimestamps.h"

#include "../src/CpuRasterizer.h"

#include "platforms/Clock.h"
#include "rhi/Error.h"

#include <algorithm>
#include <string>

namespace lpv::rhi::gl {

TimestampSource GlTimestamps::sourceFor(std::string_view renderer) {
    return isCpuRasterizer(renderer) ? TimestampSource::CpuFinished : TimestampSource::GpuQueries;
}

void GlTimestamps::create(const Functions& gl, TimestampSource source, uint32_t perFrame, uint32_t sets) {
    gl_ = &gl;
    source_ = source;
    perFrame_ = perFrame;
    sets_.resize(sets);
    for (Set& s : sets_) {
        s.written.assign(perFrame, 0);
        if (source == TimestampSource::CpuFinished) s.cpuNs.assign(perFrame, 0);
        if (source == TimestampSource::GpuQueries && perFrame > 0) {
            s.queries.resize(perFrame);
            gl.glCreateQueries(GL_TIMESTAMP, GLsizei(perFrame), s.queries.data());
        }
    }
}

void GlTimestamps::destroy() {
    for (Set& s : sets_)
        if (!s.queries.empty()) gl_->glDeleteQueries(GLsizei(s.queries.size()), s.queries.data());
    sets_.clear();
}

void GlTimestamps::beginFrame(uint64_t frame) {
    Set& s = setFor(frame);
    s.frame = frame;
    s.ended = false;
    std::fill(s.written.begin(), s.written.end(), uint8_t(0));
}

void GlTimestamps::write(uint64_t frame, uint32_t slot) {
    if (slot >= perFrame_)
        throw Error("timestamp slot " + std::to_string(slot) + " >= maxTimestampsPerFrame " +
                    std::to_string(perFrame_));
    Set& s = setFor(frame);
    if (s.written[slot])
        throw Error("timestamp slot " + std::to_string(slot) + " written twice in one frame");
    s.written[slot] = 1;
    if (source_ == TimestampSource::CpuFinished) {
        gl_->glFinish();
        s.cpuNs[slot] = platforms::nowNanoseconds();
    } else {
        gl_->glQueryCounter(s.queries[slot], GL_TIMESTAMP);
    }
}

void GlTimestamps::endFrame(uint64_t frame) {
    setFor(frame).ended = true;
}

bool GlTimestamps::read(uint64_t frame, std::span<uint64_t> out) {
    if (out.size() > perFrame_) throw Error("readTimestamps: more slots than maxTimestampsPerFrame");
    if (frame == 0 || sets_.empty()) return false;
    Set& s = setFor(frame);
    if (s.frame != frame || !s.ended) return false;
    if (source_ == TimestampSource::GpuQueries) {
        for (size_t i = 0; i < out.size(); ++i) {
            if (!s.written[i]) continue;
            GLint available = 0;
            gl_->glGetQueryObjectiv(s.queries[i], GL_QUERY_RESULT_AVAILABLE, &available);
            if (!available) return false;
        }
    }
    for (size_t i = 0; i < out.size(); ++i) {
        uint64_t ns = 0;
        if (s.written[i]) {
            if (source_ == TimestampSource::CpuFinished) {
                ns = s.cpuNs[i];
            } else {
                GLuint64 v = 0;
                gl_->glGetQueryObjectui64v(s.queries[i], GL_QUERY_RESULT, &v);
                ns = v;
            }
        }
        out[i] = ns;
    }
    return true;
}

} // namespace lpv::rhi::gl
