// Console-class platform profiles (x360, ps3, pc): the frame and GI budgets a game ships to, and
// the hardware throughput the frame profiler's cost model turns work counts into milliseconds
// with. The numbers live in data files (platforms/profiles/*.toml, each with its source) that are
// built into the binary; a path to another TOML file of the same shape works too.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lpv::platforms {

struct Throughput {
    double aluGflops = 0;          // shader ALU, GFLOP/s
    double texelRateG = 0;         // filtered texel fetches, G/s
    double fillRateGpix = 0;       // ROP output, Gpixels/s
    double memoryGBs = 0;          // main graphics memory bandwidth, GB/s
    double edramGBs = 0;           // render-target memory (Xbox 360 eDRAM), GB/s; 0 when none
    double triangleRateM = 0;      // triangle setup, M/s
    bool textureBlocksAlu = false; // a texture fetch occupies an ALU slot (G70-class pixel pipes)
};

struct PlatformProfile {
    std::string name;
    std::string description;
    std::string source; // the file it came from (built-in name or path)
    double frameBudgetMs = 0;
    double giBudgetMs = 0;
    // What the GI time budget holds: the time this profile's throughput predicts for the GI
    // passes' work ([gi] time = "predicted", the consoles, whose GPU this machine is not), or the
    // time measured on this device ("measured").
    bool giTimePredicted = false;
    uint64_t giMemoryBudgetBytes = 0;
    uint64_t gpuMemoryBytes = 0;
    uint32_t maxVolumeSize = 0;
    std::vector<std::string> shFormats; // "rgba8", "rgba16f", "rgba32f"
    Throughput throughput;

    bool allowsShFormat(std::string_view format) const;
};

// Built-in names: x360, ps3, pc.
std::vector<std::string> builtinProfileNames();
// A built-in name, or a path to a TOML file. Throws std::runtime_error naming the file, the line
// and the problem (unknown or missing key, wrong type, malformed TOML), or the path and the OS's
// reason when the file cannot be read.
PlatformProfile loadPlatformProfile(std::string_view nameOrPath);
PlatformProfile parsePlatformProfile(std::string_view toml, const std::string& sourceName);

} // namespace lpv::platforms
