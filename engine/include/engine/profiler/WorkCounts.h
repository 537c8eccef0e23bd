// Device-independent work done by a pass, derived from its real dispatch and draw parameters. The
// console cost model turns these into predicted milliseconds on the Xbox 360 and PS3.
#pragma once

#include <cstdint>

namespace lpv::engine {

struct WorkCounts {
    uint64_t cells = 0;         // volume cells processed (informational)
    uint64_t texelsRead = 0;    // filtered texture fetches
    uint64_t texelsWritten = 0; // texels written through ROPs or image stores
    uint64_t bytesMoved = 0;    // memory traffic, reads plus writes
    uint64_t aluOps = 0;        // shader floating-point operations (a MAD counts 2)
    uint64_t pixelsShaded = 0;  // fragment shader invocations
    uint64_t primitives = 0;    // triangles or points set up

    WorkCounts& operator+=(const WorkCounts& o) {
        cells += o.cells;
        texelsRead += o.texelsRead;
        texelsWritten += o.texelsWritten;
        bytesMoved += o.bytesMoved;
        aluOps += o.aluOps;
        pixelsShaded += o.pixelsShaded;
        primitives += o.primitives;
        return *this;
    }
    WorkCounts operator*(uint64_t n) const {
        return {cells * n,  texelsRead * n,   texelsWritten * n, bytesMoved * n,
                aluOps * n, pixelsShaded * n, primitives * n};
    }
    bool empty() const {
        return !(cells | texelsRead | texelsWritten | bytesMoved | aluOps | pixelsShaded | primitives);
    }
    friend bool operator==(const WorkCounts&, const WorkCounts&) = default;
};

} // namespace lpv::engine
