// The console cost model: a roofline over the units of a platform profile. A pass takes as long as
// its busiest unit - shader ALU, texture fetch, memory bandwidth, ROP fill or triangle setup - at
// the profile's throughput (platforms/profiles/*.toml, each constant with its source). On
// G70-class hardware (PS3) a texture fetch occupies an ALU slot, so there ALU and texture time add.
// Texture work counts filtered (bilinear) fetches: a trilinear or 3D fetch counts 2, as on both
// consoles' texture units.
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "platforms/PlatformProfile.h"

namespace lpv::engine {

struct CostPrediction {
    double ms = 0.0;
    const char* bottleneck = "none"; // "alu", "alu+texture", "texture", "memory", "fill", "setup"
    double aluMs = 0, textureMs = 0, memoryMs = 0, fillMs = 0, setupMs = 0;
};

CostPrediction predictCost(const WorkCounts& work, const platforms::Throughput& throughput);

} // namespace lpv::engine
