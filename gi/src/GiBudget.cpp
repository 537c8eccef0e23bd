// GI resource plan and its check against the platform profile.
#include "gi/GiBudget.h"

#include "gi/GatheredReflection.h"
#include "gi/SurfaceVoxels.h"
#include "gi/VplGather.h"
#include "gi/VplWindows.h"

#include "gi/LpvVolumes.h"
#include "gi/PointLightInjection.h"
#include "gi/SpotLightRsms.h"
#include "rhi/Format.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace lpv::gi {

std::vector<GiResource> giResources(const LpvSettings& s) {
    const uint64_t rsm = uint64_t(s.rsmSize) * s.rsmSize;
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    const uint64_t shBytes = rhi::bytesPerPixel(shTextureFormat(s.shFormat));
    // Injection blends in float: 32-bit floats for rgba32f volumes, half floats otherwise.
    const uint64_t injectBytes = s.shFormat == ShFormat::Rgba32f ? 16 : 8;
    uint64_t packedBytes = 0;
    for (uint32_t t = 0; t < packedTexelCount(s.shFormat); ++t)
        packedBytes += rhi::bytesPerPixel(packedTexelFormat(s.shFormat, t));
    const uint64_t partialSize = partialSumSize(s); // with the shell around, for several cascades
    const uint64_t partialCells = partialSize * partialSize * partialSize;
    const uint64_t gvCells = uint64_t(s.gridSize + 1) * (s.gridSize + 1) * (s.gridSize + 1);
    std::vector<GiResource> out = {
        {"rsm depth", "gi.rsm", rsm * 4},
        {"rsm normal", "gi.rsm", rsm * 8},
        {"rsm flux", "gi.rsm", rsm * 8},
        {"vpl buffer", "gi.vpl", uint64_t(s.vplSlots()) * 48},
        {"injection volume (3 SH textures)", "gi.lpv", 3 * cells * injectBytes},
        {"propagation partial sums, ping (packed)", "gi.lpv", partialCells * packedBytes},
        {"propagation partial sums, pong (packed)", "gi.lpv", partialCells * packedBytes},
        {"accumulation (3 SH textures)", "gi.lpv", 3 * cells * shBytes},
        {"analytic light buffers (one per cascade)", "gi.lights",
         s.cascades * PointLightInjection::kBufferBytes},
    };
    // Every further cascade keeps its own result, and its VPLs (its update may be split over two
    // frames); the scratch volumes and the RSM above serve them in turn, or (gi.cascades_together)
    // each has its own, to be drawn and propagated with the others.
    for (uint32_t c = 1; c < s.cascades; ++c) {
        const std::string cascade = ", cascade " + std::to_string(c);
        out.push_back({"accumulation" + cascade + " (3 SH textures)", "gi.lpv", 3 * cells * shBytes});
        out.push_back({"vpl buffer" + cascade, "gi.vpl", uint64_t(s.vplSlots()) * 48});
        if (!s.propagateTogether()) continue;
        out.push_back({"rsm depth, normal, flux" + cascade, "gi.rsm", rsm * (4 + 8 + 8)});
        out.push_back({"injection volume" + cascade + " (3 SH textures)", "gi.lpv", 3 * cells * injectBytes});
        out.push_back(
            {"propagation partial sums, ping" + cascade + " (packed)", "gi.lpv", partialCells * packedBytes});
        out.push_back(
            {"propagation partial sums, pong" + cascade + " (packed)", "gi.lpv", partialCells * packedBytes});
    }
    // Spot lights with their own RSM (SpotLightRsms): an RSM and a VPL buffer each; point lights
    // six of each, a cube.
    for (uint32_t k = 0; k < s.lightRsms; ++k) {
        const std::string light = "spot light " + std::to_string(k);
        out.push_back({light + " rsm depth, normal, flux", "gi.rsm", rsm * (4 + 8 + 8)});
        out.push_back({light + " vpl buffer", "gi.vpl", uint64_t(spotLightVplSlots(s)) * 48});
    }
    for (uint32_t k = 0; k < s.pointLightRsms; ++k) {
        const std::string light = "point light " + std::to_string(k);
        out.push_back(
            {light + " cube rsm depth, normal, flux (6 faces)", "gi.rsm", kCubeFaces * rsm * (4 + 8 + 8)});
        out.push_back(
            {light + " vpl buffers (6 faces)", "gi.vpl", kCubeFaces * uint64_t(spotLightVplSlots(s)) * 48});
    }
    if (s.occlusion) {
        // gi.cascades_together: every cascade's geometry volume is built at once, each in its own.
        const uint64_t sets = s.propagateTogether() ? s.cascades : 1;
        out.push_back({"geometry volume coverage, light surfels", "gi.gv", sets * gvCells * 4});
        out.push_back({"geometry volume coverage, camera surfels", "gi.gv", sets * gvCells * 4});
        // One per cascade with gi.lookup_occlusion: the lookup reads each cascade's.
        out.push_back({"face transmittance", "gi.gv", cells * 4 * s.faceVolumes()});
        // gi.coarse_camera_occlusion: the coarse cascades' camera areas, 3 x R32UI a GV cell.
        if (s.cameraAreas())
            out.push_back({"geometry volume coverage, camera areas", "gi.gv", sets * gvCells * 12});
    }
    if (s.bounces > 1) { // needs occlusion (readLpvSettings)
        // Two R32UI a GV cell: a fixed-point mean albedo and a surfel count (gv_albedo_sums_body.glsl).
        out.push_back({"geometry volume albedo sums", "gi.gv", gvCells * 8});
        out.push_back({"surfel albedo", "gi.gv", cells * 4});
        out.push_back({"bounce scratch (3 SH textures)", "gi.lpv", 3 * cells * shBytes});
        // gi.cascades_together: the finest cascade's further bounce propagates with the cascades,
        // in volumes of its own, from its first bounce kept apart (MultipleBounces).
        if (s.propagateTogether()) {
            out.push_back({"bounce injection volume (3 SH textures)", "gi.lpv", 3 * cells * injectBytes});
            out.push_back(
                {"bounce partial sums, ping and pong (packed)", "gi.lpv", 2 * partialCells * packedBytes});
            out.push_back({"first bounce, finest cascade (3 SH textures)", "gi.lpv", 3 * cells * shBytes});
        }
    }
    // gi.gather: the gathered cascades' first bounce kept apart for the lookup to take out (the
    // gather's target is screen-sized, counted with the lookup's targets in render.lighting).
    if (s.gather) {
        for (uint32_t c = 0; c < std::min(s.cascades, VplGather::kCascades); ++c)
            out.push_back(
                {"first bounce kept for gi.gather, cascade " + std::to_string(c) + " (3 SH textures)",
                 "gi.lpv", 3 * cells * shBytes});
        // The gather's own VPLs of those cascades' sun (creases split: VplClustering).
        for (uint32_t c = 0; c < std::min(s.cascades, VplGather::kCascades); ++c)
            out.push_back(
                {"gather vpl buffer, cascade " + std::to_string(c), "gi.vpl", uint64_t(s.vplSlots()) * 48});
        // Which of them each texel's window takes (VplWindows).
        for (uint32_t c = 0; c < std::min(s.cascades, VplGather::kCascades); ++c)
            out.push_back({"gather vpl windows, cascade " + std::to_string(c), "gi.vpl",
                           VplWindows::bytes(s.vplGridSide())});
        // Its visibility's faces: the scene's surfaces on the gathered cascades' cells.
        if (s.occlusion)
            out.push_back({"surface faces of the gathered cascades (gi.gather)", "gi.lpv",
                           SurfaceVoxels::bytes(s.gridSize)});
        // With further bounces, the second is reflected from the gathered first (GatheredReflection).
        if (s.bounces > 1) {
            out.push_back(
                {"second bounce VPL list (gi.gather)", "gi.vpl", GatheredReflection::listBytes(s.gridSize)});
            out.push_back({"second bounce face slots (gi.gather)", "gi.lpv",
                           GatheredReflection::slotBytes(s.gridSize)});
        }
        // And the third, from the second's list (gi.bounces = 3).
        if (s.bounces > 2) {
            out.push_back(
                {"third bounce VPL list (gi.gather)", "gi.vpl", GatheredReflection::listBytes(s.gridSize)});
            out.push_back(
                {"third bounce face slots (gi.gather)", "gi.lpv", GatheredReflection::slotBytes(s.gridSize)});
        }
    }
    return out;
}

uint64_t giBytes(const std::vector<GiResource>& resources) {
    uint64_t sum = 0;
    for (const GiResource& r : resources)
        sum += r.bytes;
    return sum;
}

GiConfigResult checkGiBudget(const LpvSettings& s, const platforms::PlatformProfile& profile) {
    if (!profile.allowsShFormat(shFormatName(s.shFormat))) {
        std::string allowed;
        for (const auto& f : profile.shFormats)
            allowed += (allowed.empty() ? "" : ", ") + f;
        return GiConfigResult::refused("gi.sh_format", "gi.sh_format '" +
                                                           std::string(shFormatName(s.shFormat)) +
                                                           "' is not allowed by platform '" + profile.name +
                                                           "' (allowed: " + allowed + ")");
    }
    if (s.gridSize > profile.maxVolumeSize)
        return GiConfigResult::refused(
            "gi.grid_size", "gi.grid_size " + std::to_string(s.gridSize) + " exceeds platform '" +
                                profile.name + "' limit of " + std::to_string(profile.maxVolumeSize));
    std::vector<GiResource> resources = giResources(s);
    const uint64_t total = giBytes(resources);
    if (total <= profile.giMemoryBudgetBytes) return {};
    return GiConfigResult::refused({},
                                   "GI configuration needs " + std::to_string(total) +
                                       " bytes, over platform '" + profile.name + "' GI memory budget of " +
                                       std::to_string(profile.giMemoryBudgetBytes) + " bytes by " +
                                       std::to_string(total - profile.giMemoryBudgetBytes),
                                   std::move(resources));
}

std::string GiConfigResult::message() const {
    std::string text = reason;
    if (!resources.empty()) text += ":";
    for (const GiResource& r : resources)
        text += "\n  " + r.category + " " + r.name + ": " + std::to_string(r.bytes) + " bytes";
    return text;
}

GiConfigResult GiConfigResult::refused(std::string setting, std::string reason,
                                       std::vector<GiResource> resources) {
    GiConfigResult r;
    r.accepted = false;
    r.setting = std::move(setting);
    r.reason = std::move(reason);
    r.resources = std::move(resources);
    return r;
}

} // namespace lpv::gi
