// The one place a backend is chosen. Order for "auto": Vulkan, then OpenGL. The null backend is
// only made when asked for by name.
#include "BackendFactory.h"

#include "platforms/Log.h"
#include "rhi/Error.h"

#include <array>
#include <string>

namespace lpv::rhi {
namespace {

struct BackendEntry {
    BackendKind kind;
    std::string_view name;
    std::unique_ptr<Device> (*create)(const DeviceConfig&);
};

constexpr std::array<BackendEntry, 3> kBackends{{
    {BackendKind::Vulkan, "vulkan", &createVulkanDevice},
    {BackendKind::OpenGL, "gl", &createGlDevice},
    {BackendKind::Null, "null", &createNullDevice},
}};
static_assert(kBackends.size() == 3, "every BackendKind but Auto has one entry");

const BackendEntry& entry(BackendKind kind) {
    for (const auto& e : kBackends)
        if (e.kind == kind) return e;
    throw Error("no backend entry for kind " + std::to_string(int(kind)));
}

BackendKind otherBackend(BackendKind kind) {
    return kind == BackendKind::Vulkan ? BackendKind::OpenGL : BackendKind::Vulkan;
}

} // namespace

std::string_view backendName(BackendKind kind) {
    return kind == BackendKind::Auto ? std::string_view("auto") : entry(kind).name;
}

std::optional<BackendKind> parseBackend(std::string_view name) {
    if (name == "auto") return BackendKind::Auto;
    if (name == "opengl") return BackendKind::OpenGL;
    for (const auto& e : kBackends)
        if (e.name == name) return e.kind;
    return std::nullopt;
}

std::string validBackendNames() {
    return "auto, gl (or opengl), vulkan, null";
}

std::optional<GlHeadless> parseGlHeadless(std::string_view name) {
    if (name == "egl") return GlHeadless::EglSurfaceless;
    if (name == "osmesa") return GlHeadless::OSMesa;
    return std::nullopt;
}

std::string_view glHeadlessName(GlHeadless h) {
    return h == GlHeadless::OSMesa ? "osmesa" : "egl";
}

std::unique_ptr<Device> createDevice(const DeviceConfig& config) {
    const BackendKind first = config.backend == BackendKind::Auto ? BackendKind::Vulkan : config.backend;
    try {
        return entry(first).create(config);
    } catch (const BackendUnavailable& e) {
        const bool canFallBack =
            first != BackendKind::Null && (config.allowFallback || config.backend == BackendKind::Auto);
        if (!canFallBack)
            throw BackendUnavailable(std::string("backend '") + std::string(entry(first).name) +
                                     "' could not start: " + e.what() + " (fallback not allowed)");
        const BackendKind second = otherBackend(first);
        log::warn(std::string("rhi: backend '") + std::string(entry(first).name) + "' unavailable (" +
                  e.what() + "); falling back to '" + std::string(entry(second).name) + "'");
        try {
            return entry(second).create(config);
        } catch (const BackendUnavailable& e2) {
            throw BackendUnavailable(std::string("no backend could start: ") +
                                     std::string(entry(first).name) + ": " + e.what() + "; " +
                                     std::string(entry(second).name) + ": " + e2.what());
        }
    }
}

std::string_view timestampSourceName(TimestampSource s) {
    switch (s) {
    case TimestampSource::None:
        return "none";
    case TimestampSource::GpuQueries:
        return "gpu-timestamp";
    case TimestampSource::CpuFinished:
        return "cpu-after-finish";
    case TimestampSource::Simulated:
        return "simulated";
    }
    return "?";
}

} // namespace lpv::rhi
