// Work counts per GI pass. Each figure follows the shader: what a thread reads, computes and
// writes, times the threads dispatched (or points/pixels drawn).
#include "gi/GiWork.h"

#include "gi/GeometryVolume.h"
#include "gi/LpvVolumes.h"
#include "gi/SpotLightRsms.h"
#include "gi/SurfaceVoxels.h"
#include "rhi/Format.h"

namespace lpv::gi {

using engine::WorkCounts;

WorkCounts rsmWork(const LpvSettings& s, uint64_t triangles) {
    const uint64_t texels = uint64_t(s.rsmSize) * s.rsmSize;
    WorkCounts w;
    w.primitives = triangles;
    w.pixelsShaded = texels;
    w.texelsRead = texels;        // albedo texture
    w.texelsWritten = texels * 3; // normal, flux, depth
    w.aluOps = texels * 20;
    w.bytesMoved = texels * (8 + 8 + 4 + 4);
    return w;
}

WorkCounts surfaceVoxelsWork(const LpvSettings& s, uint64_t triangles) {
    // An estimate: the surfaces of a room cross each cell column about twice per axis, each time
    // in k^2 samples (SurfaceVoxels::kSamplesPerSide), each adding to its face's area; and the
    // areas' clear.
    const uint64_t k = SurfaceVoxels::kSamplesPerSide;
    const uint64_t fragments = uint64_t(3) * 2 * s.gridSize * s.gridSize * k * k;
    const uint64_t faces = uint64_t(3) * s.gridSize * s.gridSize * s.gridSize;
    WorkCounts w;
    w.primitives = triangles * 3;
    w.pixelsShaded = fragments;
    w.texelsWritten = fragments + faces;
    w.aluOps = triangles * 3 * 40 + fragments * 10;
    w.bytesMoved = fragments * 4 + faces * 4;
    return w;
}

WorkCounts vplClusterWork(const LpvSettings& s) {
    const uint64_t texels = uint64_t(s.rsmSize) * s.rsmSize;
    WorkCounts w;
    // The block's depth range, then one pass per depth layer (each reads every depth, flux and
    // normal of its own texels).
    w.texelsRead = texels * 5;
    w.aluOps = texels * 40; // unproject, weight, three weighted sums, the layer test
    w.bytesMoved = texels * (4 + 8 + 8) + uint64_t(s.vplSlots()) * 48;
    return w;
}

WorkCounts gatherVplWork(const LpvSettings& s) {
    const uint64_t texels = uint64_t(s.rsmSize) * s.rsmSize;
    WorkCounts w;
    // Per side of an edge up to three scans of the block (planeOf in vpl_cluster.comp: its
    // brightest texel, the flux on and off that plane, the flux on the other candidate), each
    // reading a texel's depth, normal and flux and unprojecting it, and the slots; a block whose
    // texels leave their plane clusters again (a share of the blocks, not counted). Before them,
    // the gaps to each texel's two neighbours (their depths read, three texels unprojected).
    w.texelsRead = texels * (2 * 3 * 3 + 2);
    w.aluOps = texels * (2 * 3 * 30 + 3 * 20);
    w.bytesMoved = texels * (4 + 8 + 8) + uint64_t(s.vplSlots()) * 48;
    return w;
}

WorkCounts injectWork(const LpvSettings& s, uint64_t extraVpls, VolumeDraw draw) {
    const uint64_t injectBytes = s.shFormat == ShFormat::Rgba32f ? 16 : 8;
    // Every slot is drawn (an empty one is parked outside the volume).
    const uint64_t vpls = s.vplSlots() + extraVpls;
    WorkCounts w;
    // Every VPL is submitted once, or once per slice (one slice keeps it).
    w.primitives = vpls * (draw == VolumeDraw::Layered ? 1 : s.gridSize);
    w.aluOps = w.primitives * 20;
    w.pixelsShaded = vpls;
    w.texelsWritten = vpls * 3;
    w.bytesMoved = w.primitives * 48 + w.texelsWritten * injectBytes * 2; // blending reads and writes
    w.cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    return w;
}

WorkCounts lightRsmWork(const LpvSettings& s, uint32_t rsms, uint64_t triangles) {
    // Each RSM: the scene in its frustum into a spot RSM of gi.rsm_size (one more position
    // interpolant and the cone, window and solid angle per texel), clustered like the sun's into
    // fewer VPLs.
    const uint64_t texels = uint64_t(s.rsmSize) * s.rsmSize;
    WorkCounts one = rsmWork(s, 0);
    one.aluOps += texels * 15;
    WorkCounts cluster = vplClusterWork(s);
    cluster.bytesMoved -= (uint64_t(s.vplSlots()) - spotLightVplSlots(s)) * 48;
    one += cluster;
    WorkCounts all = one * rsms;
    all.primitives += triangles;
    return all;
}

WorkCounts propagateWork(const LpvSettings& s) {
    // The shipped kernel (propagate_body.glsl): per cell and iteration, 3 fetched cells of
    // partial sums, packedTexelCount texels each (the 2x2 column's ring and the slice above; the
    // rest come from registers), the injected x (3 texels), one store of the partial sum (3
    // texels on the last iteration, 1 per channel).
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    const uint64_t packed = packedTexelCount(s.shFormat);
    uint64_t packedBytes = 0;
    for (uint32_t t = 0; t < packed; ++t)
        packedBytes += rhi::bytesPerPixel(packedTexelFormat(s.shFormat, t));
    const uint64_t injectBytes = s.shFormat == ShFormat::Rgba32f ? 16 : 8;
    WorkCounts one;
    one.cells = cells;
    one.texelsRead = cells * (3 * packed + 3);
    one.texelsWritten = cells * packed;
    // 6 neighbours x 3 channels x (6 multiply-adds + 4 sums of the +-e pair), the x term, and the
    // unpacking of 4 cells' and packing of one cell's 12 coefficients.
    one.aluOps = cells * (6 * 3 * 10 + 12 + 5 * 12);
    // Each packed texel comes from memory about once (texture cache), x once, one store.
    one.bytesMoved = cells * (packedBytes + 3 * injectBytes + packedBytes);
    WorkCounts all = one * s.iterations;
    if (!partialSumShell(s)) return all;
    // With a shell (several cascades), the seed before the first iteration: x copied into the
    // partial sums, and the shell around them (beyond the border) written into both ping and pong;
    // a cascade with a coarser one around samples it there (3 trilinear fetches, two bilinear
    // each; counted for every cascade).
    const uint64_t padded = partialSumSize(s);
    const uint64_t shell = padded * padded * padded - cells;
    WorkCounts seed;
    seed.cells = cells + shell;
    seed.texelsRead = cells * 3 + shell * 6;
    seed.texelsWritten = (cells + 2 * shell) * packed;
    seed.aluOps = (cells + shell) * (12 + 5 * 12);
    seed.bytesMoved = cells * 3 * injectBytes + (cells + 2 * shell) * packedBytes;
    all += seed;
    return all;
}

WorkCounts bounceWork(const LpvSettings& s) {
    if (s.bounces < 2) return {};
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    const uint64_t shBytes = rhi::bytesPerPixel(shTextureFormat(s.shFormat));
    const uint64_t injectBytes = s.shFormat == ShFormat::Rgba32f ? 16 : 8;
    WorkCounts reflect;
    // lpv_reflect_body.glsl: the cell's 3 SH texels, 4 face-transmittance texels and its albedo;
    // 6 faces x 3 channels of a few multiply-adds; 3 injection texels written.
    reflect.cells = cells;
    reflect.texelsRead = cells * (3 + 4 + 1);
    reflect.texelsWritten = cells * 3;
    reflect.aluOps = cells * (6 * (3 * 6 + 8) + 20);
    reflect.bytesMoved = cells * (3 * shBytes + 5 * 4 + 3 * injectBytes);
    WorkCounts sum;
    // lpv_bounce_add_body.glsl: 3 texels read from each volume, 3 written.
    sum.texelsRead = cells * 6;
    sum.texelsWritten = cells * 3;
    sum.aluOps = cells * 3 * 4 * 2;
    sum.bytesMoved = cells * 9 * shBytes;
    WorkCounts one = reflect;
    one += propagateWork(s);
    one += sum;
    return one * (s.bounces - 1);
}

WorkCounts gatherPropagationWork(const LpvSettings& s) {
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    const uint64_t bpp = rhi::bytesPerPixel(shTextureFormat(s.shFormat));
    WorkCounts one;
    one.cells = cells;
    one.texelsRead = cells * (6 * 3 + 3); // 6 neighbours x 3 channels, plus the accumulation
    one.texelsWritten = cells * 6;        // next iteration and accumulation, 3 channels each
    // Per face and channel after constant folding: a 3-term dot (5), a clamp (1), a 2-term update (4).
    one.aluOps = cells * (6 * 5 * 3 * 10 + 12);
    // Neighbour reads hit the texture cache: each texel comes from memory about once.
    one.bytesMoved = cells * bpp * (3 + 3 + 6);
    return one * s.iterations;
}

WorkCounts occlusionWork(const LpvSettings& s, uint64_t cameraSamples, VolumeDraw draw,
                         uint64_t lightRsmSurfels) {
    const uint64_t slices = draw == VolumeDraw::Layered ? 1 : s.gridSize + 1;
    // A camera sample draws GeometryVolume::kCameraPointsPerSample points (itself, the half-way
    // points to two neighbours on its surface, the edges of its footprint), each submitted even
    // where it is parked. This engine marks them with a compute pass and integer atomics
    // (gv_camera_marks.comp), which the consoles' GPUs do not have: on them the points are drawn
    // into blended targets, as this engine did before, and that is what is counted.
    const uint64_t cameraPoints = cameraSamples * GeometryVolume::kCameraPointsPerSample;
    const uint64_t surfels = s.vplSlots() + cameraPoints + lightRsmSurfels;
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    WorkCounts w;
    // Every surfel is submitted once, or once per slice (camera points fetch their sample's depth,
    // normal and albedo, and all but the sample's own a neighbour's depth and normal, each time);
    // one slice keeps it.
    // Then per LPV cell the light's coverage closed over holes (a 4 x 4 patch less its corners per
    // face: 36 fetches), with camera surfels the camera's too, and one store.
    const uint64_t faceFetches = cameraSamples > 0 ? 36 + 36 : 36;
    w.primitives = surfels * slices;
    w.aluOps = w.primitives * 25 + cameraPoints * 20 * slices + cells * (cameraSamples > 0 ? 100 : 60);
    w.pixelsShaded = surfels;
    constexpr uint64_t points = GeometryVolume::kCameraPointsPerSample;
    w.texelsRead = cameraSamples * (3 * points + 2 * (points - 1)) * slices + cells * faceFetches;
    w.texelsWritten = surfels + cells;
    // The patches' fetches overlap from cell to cell: the camera's volume (RGBA8) comes from
    // memory about twice, the light's as often as its 12 corner fetches did.
    w.bytesMoved = w.primitives * 48 + surfels * 16 + cells * (12 * 8 + (cameraSamples > 0 ? 8 : 0) + 4);
    w.cells = cells;
    if (cameraSamples > 0) {
        // The camera's marks start as the cells' real gaps (gv_gaps.comp): per GV cell its centre
        // projected into the camera's view, a depth fetched and the hit compared with the centre
        // (about 70 ALU), one texel written.
        const uint64_t gvCells = uint64_t(s.gridSize + 1) * (s.gridSize + 1) * (s.gridSize + 1);
        w.texelsRead += gvCells;
        w.aluOps += gvCells * 70;
        w.texelsWritten += gvCells;
        w.bytesMoved += gvCells * (4 + 4);
    }
    return w;
}

WorkCounts cameraAreasWork(const LpvSettings& s, uint64_t cameraSamples) {
    const uint64_t gvCells = uint64_t(s.gridSize + 1) * (s.gridSize + 1) * (s.gridSize + 1);
    const uint64_t cells = uint64_t(s.gridSize) * s.gridSize * s.gridSize;
    WorkCounts w;
    // Per sample its own and its four neighbours' depth and normal; unprojecting them, the
    // crease solves toward the neighbours, the footprint's box and its split (about 500 ALU); up
    // to 2 x 2 cells x 3 axes atomic adds (all counted). The areas' volume is cleared first
    // (3 texels a GV cell), and the faces pass reads the areas at each face's 4 corners.
    w.texelsRead = cameraSamples * 10 + cells * 12;
    w.aluOps = cameraSamples * 500 + cells * 12;
    w.texelsWritten = cameraSamples * 12 + gvCells * 3;
    w.bytesMoved = cameraSamples * (10 * 8 + 12 * 8) + gvCells * 12 + cells * 12 * 4;
    return w;
}

WorkCounts lookupWork(const LpvSettings& s, uint64_t pixels) {
    WorkCounts w;
    w.pixelsShaded = pixels;
    const uint64_t lookups = s.damping ? 2 : 1;
    // Depth, normal, and 3 filtered volume fetches per lookup; a 3D (trilinear) fetch costs two
    // bilinear ones on the texture units the cost model describes. With gi.glossy, the albedo and
    // the specular table's two blocks for the glossy lobes.
    // lpv_lookup.glsl looks up the finest cascade holding the point, and the next coarser one in
    // its blend band: at most two per pixel, counted for every pixel (a wave that straddles a band
    // runs both).
    const uint64_t cascades = s.cascades < 2 ? s.cascades : 2;
    const uint64_t lobes = s.glossy ? 1 : 0;
    // With occlusion, the 3 face transmittances that keep a cascade's filter from reading across
    // walls (lpv_lookup.glsl, keptInside): the finest cascade's, or with gi.lookup_occlusion every one's.
    const uint64_t faces = s.occlusion ? 3 * (s.lookupOcclusion ? cascades : 1) : 0;
    w.texelsRead = pixels * (2 + 3 * lobes + 3 * 2 * lookups * cascades + faces);
    // Two targets: the irradiance and the glossy radiance.
    w.texelsWritten = 2 * pixels;
    // The glossy lobes (3 channels' mean directions) and their 3 more dot products per fetch; per
    // face, its share of the filter and the camera's side of it (where the view ray crossed it).
    w.aluOps = pixels * (30 + 30 * lobes + 37 * lookups * cascades + 20 * faces);
    w.bytesMoved = pixels * (4 + 8 + 4 * lobes + 8 + 8);
    w.primitives = 1;
    if (s.gather) {
        // The first bounce's 3 volumes in each of (at most) two cascades, and the gather's 4 x 4
        // average: each texel's depth, normal and gathered light.
        w.texelsRead += pixels * (3 * 2 * cascades + 16 * 3);
        w.aluOps += pixels * (20 * cascades + 16 * 25);
        w.bytesMoved += pixels * 16 * (4 + 8 + 8);
    }
    return w;
}

} // namespace lpv::gi
