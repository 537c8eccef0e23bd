// Work counts of the GI passes, derived from the same sizes the passes dispatch with, for the
// frame profiler's console cost model (engine/profiler/CostModel.h).
#pragma once

#include "engine/profiler/WorkCounts.h"
#include "gi/LpvSettings.h"

#include <cstdint>

namespace lpv::gi {

// How points reach the slices of a volume: each once, its vertex picking the slice (a layered
// pass, or the consoles' volume unwrapped into one 2D target), or each once per slice.
enum class VolumeDraw : uint8_t { Layered, PerSlice };

// `triangles`: those drawn into the RSM (ReflectiveShadowMap::record culls to the light's view).
engine::WorkCounts rsmWork(const LpvSettings& s, uint64_t triangles);
engine::WorkCounts vplClusterWork(const LpvSettings& s);
// What the same pass adds where it also writes the gather's VPLs (gi.gather's cascades).
engine::WorkCounts gatherVplWork(const LpvSettings& s);
// The scene's surfaces onto a cascade's faces (SurfaceVoxels): `triangles` drawn along each of the
// three axes, a fragment per cell column a triangle crosses.
engine::WorkCounts surfaceVoxelsWork(const LpvSettings& s, uint64_t triangles);
// `extraVpls`: VPLs of further lights in the same pass (spot and point lights with an RSM).
engine::WorkCounts injectWork(const LpvSettings& s, uint64_t extraVpls = 0,
                              VolumeDraw draw = VolumeDraw::Layered);
// The `rsms` RSMs of spot and point lights (SpotLightRsms: one per spot, six per point light) and
// their VPL clustering, once per frame; `triangles`: drawn into all of them together.
engine::WorkCounts lightRsmWork(const LpvSettings& s, uint32_t rsms, uint64_t triangles);
// All iterations of the shipped kernel.
engine::WorkCounts propagateWork(const LpvSettings& s);
// All iterations of the straightforward 5-face gather the CryEngine 3 shaders use (one cell per
// thread, every face evaluated and clamped, 3 SH textures read per neighbour, accumulation read
// and written every iteration) and the benchmark keeps as its baseline. The cost model is
// calibrated against the published console times with these counts, since that is the kernel
// those times measured.
// Bounces 2..gi.bounces of one cascade: per bounce a reflection pass, the propagation, the sum.
engine::WorkCounts bounceWork(const LpvSettings& s);
engine::WorkCounts gatherPropagationWork(const LpvSettings& s);
// The geometry volume: light and camera surfels drawn into it, then the face transmittance.
// `lightRsmSurfels`: VPLs of spot and point lights' RSMs drawn as surfels too.
engine::WorkCounts occlusionWork(const LpvSettings& s, uint64_t cameraSamples,
                                 VolumeDraw draw = VolumeDraw::Layered, uint64_t lightRsmSurfels = 0);
// A coarse cascade's camera surfels (gi.coarse_camera_occlusion), on top of occlusionWork(s, 0):
// the pass that measures each sample's footprint and adds its area (gv_camera_areas.comp), and
// the faces pass's reads of those areas.
engine::WorkCounts cameraAreasWork(const LpvSettings& s, uint64_t cameraSamples);
engine::WorkCounts lookupWork(const LpvSettings& s, uint64_t pixels);

} // namespace lpv::gi
