// Choosing a backend at startup. One enum, one factory, one fallback rule:
//   "vulkan", "gl" and "null" name a backend; "auto" tries Vulkan first, then OpenGL.
//   When the chosen backend cannot start, createDevice() throws BackendUnavailable with the
//   reason, or - if allowFallback - logs one line naming both backends and the reason, and
//   continues on the other one (Vulkan <-> OpenGL; null never falls back).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace lpv::platforms {
class Window;
}

namespace lpv::rhi {

class Device;

enum class BackendKind : uint8_t { Auto, OpenGL, Vulkan, Null };

// How the OpenGL backend gets its context when there is no window.
enum class GlHeadless : uint8_t { EglSurfaceless, OSMesa };

std::string_view backendName(BackendKind kind);
std::optional<BackendKind> parseBackend(std::string_view name);
// "auto, gl, vulkan, null": for error messages and help text.
std::string validBackendNames();
std::optional<GlHeadless> parseGlHeadless(std::string_view name);
std::string_view glHeadlessName(GlHeadless h);

enum class DebugSeverity : uint8_t { Info, Warning, Error };
struct DebugMessage {
    DebugSeverity severity = DebugSeverity::Info;
    std::string text;
};

struct DeviceConfig {
    BackendKind backend = BackendKind::Auto;
    bool allowFallback = true;
    GlHeadless glHeadless = GlHeadless::EglSurfaceless;
    // With a window the device presents to it; without one it runs headless.
    platforms::Window* window = nullptr;
    // Vulkan validation layer and GL KHR_debug output. Messages go to onDebugMessage.
    bool validation = false;
    std::function<void(const DebugMessage&)> onDebugMessage;
    uint32_t framesInFlight = 2;
    // Per-frame ring for CommandList::pushUniforms.
    uint32_t uniformRingBytes = 4u << 20;
    uint32_t maxTimestampsPerFrame = 128;
    // false: report Caps::vertexShaderLayer off even where the device has it, so the callers'
    // one-pass-per-slice paths can be run and compared against the layered ones.
    bool vertexShaderLayer = true;
    // Set: report Caps::maskedBranches as given instead of as the device is, so both of the
    // callers' paths can be run and compared on any device.
    std::optional<bool> maskedBranches;
    // False: report no Caps::multiDrawIndirect, as a device without it, so that the one call per
    // draw that callers fall back to can be run and compared (true changes nothing).
    std::optional<bool> multiDrawIndirect;
    // Set: report at most this many storage image bindings (Caps::storageImageBindings), so the
    // callers' paths for OpenGL's minimum of 8 run, and are compared, on any device.
    std::optional<uint32_t> storageImageBindings;
    // Set: report at most this many fragment texture bindings (Caps::fragmentTextureBindings), so
    // what a caller does on a device with fewer can be run on any device.
    std::optional<uint32_t> fragmentTextureBindings;
    // A full barrier after every dispatch, render pass and transfer (CommandList.h's old rule) on
    // both APIs, instead of one only where a later command needs it. For ruling a suspected
    // synchronization bug in or out in one run; the environment variable
    // LPV_CONSERVATIVE_BARRIERS=1 sets it too.
    bool conservativeBarriers = false;
    // Vulkan: set, keep every texture in VK_IMAGE_LAYOUT_GENERAL (true) or in the layout of each
    // use (false) instead of as the device prefers: GENERAL where layouts cost nothing (a CPU
    // device, or one with VK_KHR_unified_image_layouts), so a render pass then needs a barrier
    // only where it reads or writes what an earlier command left unordered. For running both
    // paths on any device.
    std::optional<bool> unifiedImageLayouts;
};

// Throws BackendUnavailable when no allowed backend starts.
std::unique_ptr<Device> createDevice(const DeviceConfig& config);

} // namespace lpv::rhi
