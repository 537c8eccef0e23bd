// The backends a benchmark runs on, named as the README and the tests name them, and the
// --backends option that picks some of them (both benchmarks share it).
#pragma once

#include "rhi/Backend.h"
#include "rhi/Device.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lpv::bench {

struct BenchBackend {
    std::string name;
    rhi::BackendKind kind;
    rhi::GlHeadless gl = rhi::GlHeadless::EglSurfaceless;
};

inline std::vector<BenchBackend> allBenchBackends() {
    return {{"vulkan", rhi::BackendKind::Vulkan},
            {"gl-egl", rhi::BackendKind::OpenGL, rhi::GlHeadless::EglSurfaceless},
            {"gl-osmesa", rhi::BackendKind::OpenGL, rhi::GlHeadless::OSMesa}};
}

// A benchmark measures the backend it names: no fallback to another.
inline std::unique_ptr<rhi::Device> makeDevice(const BenchBackend& b) {
    rhi::DeviceConfig config;
    config.backend = b.kind;
    config.glHeadless = b.gl;
    config.allowFallback = false;
    return rhi::createDevice(config);
}

// --backends=vulkan,gl-egl: `chosen` (every backend unless given) becomes the named ones, in the
// order given; an unknown name is a usage error that lists the known ones.
inline void addBackendsOption(CLI::App& app, std::vector<BenchBackend>& chosen) {
    chosen = allBenchBackends();
    std::vector<std::string> names;
    for (const BenchBackend& b : chosen)
        names.push_back(b.name);
    app.add_option_function<std::vector<std::string>>(
           "--backends",
           [&chosen](const std::vector<std::string>& picked) {
               chosen.clear();
               for (const std::string& n : picked) {
                   // Twice would measure it twice, in rows that look like two backends' figures.
                   for (const BenchBackend& b : chosen)
                       if (b.name == n) throw CLI::ValidationError("--backends", n + " is named twice");
                   for (const BenchBackend& b : allBenchBackends())
                       if (b.name == n) chosen.push_back(b);
               }
           },
           "Backends to measure, comma-separated (default: all)")
        ->delimiter(',')
        ->check(CLI::IsMember(names));
}

} // namespace lpv::bench
