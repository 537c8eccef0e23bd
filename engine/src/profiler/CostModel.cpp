// Roofline prediction of a pass's time on a console from its work counts.
#include "engine/profiler/CostModel.h"

namespace lpv::engine {

CostPrediction predictCost(const WorkCounts& w, const platforms::Throughput& t) {
    const auto ms = [](double amount, double perSecond) {
        return perSecond > 0 ? amount / perSecond * 1e3 : 0.0;
    };
    CostPrediction p;
    p.aluMs = ms(double(w.aluOps), t.aluGflops * 1e9);
    p.textureMs = ms(double(w.texelsRead), t.texelRateG * 1e9);
    p.memoryMs = ms(double(w.bytesMoved), t.memoryGBs * 1e9);
    p.fillMs = ms(double(w.texelsWritten), t.fillRateGpix * 1e9);
    p.setupMs = ms(double(w.primitives), t.triangleRateM * 1e6);
    // Where a fetch takes an ALU slot, shading time is ALU plus texture time.
    const double shadeMs = t.textureBlocksAlu ? p.aluMs + p.textureMs : p.aluMs;
    const std::pair<double, const char*> units[] = {{shadeMs, t.textureBlocksAlu ? "alu+texture" : "alu"},
                                                    {p.textureMs, "texture"},
                                                    {p.memoryMs, "memory"},
                                                    {p.fillMs, "fill"},
                                                    {p.setupMs, "setup"}};
    for (const auto& [value, name] : units)
        if (value > p.ms) {
            p.ms = value;
            p.bottleneck = name;
        }
    return p;
}

} // namespace lpv::engine
