// Multiple bounces with gi.gather, the second bounce's reflection (gi/GatheredReflection.h): the
// light each blocking face of the geometry volume receives is gathered from the VPLs (flux x cos x
// cos / (pi r^2), as vpl_gather.frag gathers it for a pixel), not read from the propagated first
// bounce, which scatters within a few cells and leaves far walls and ceilings unlit
// (docs/gi-fidelity.md). Per cell and per face, as lpv_reflect_body.glsl:
//   received  = irradiance on the face, facing back into the cell, x the face's area,
//   reflected = albedo x (1 - face transmittance) x received, injected into this cell as a VPL of
//               that flux whose normal points back into the cell: half a cell in front of the face.
// Interleaved: cell c sums the clusters at ((c.x + c.y) mod 2, (c.y + c.z) mod 2), times 4, so that
// every 2 x 2 block of cells on a plane of the grid covers each cluster once; propagation and the
// pixels' gather blur the rest. One dispatch per set of VPLs; each after the first adds to the
// injection volume and to the faces' flux.
// Each reflecting face is also listed as a VPL of the second bounce (position: the face's centre,
// normal: back into the cell), which the per-pixel gather sums as it sums the first bounce's: the
// first dispatch gives each cell's blocking faces consecutive slots (faceSlots), the later ones add
// to them. The list is 16 lists, one per cell phase ((c.x + c.y) mod 4 + 4 ((c.y + c.z) mod 4)):
// a pixel sums one phase's whole list, so what it sums does not depend on the order the slots
// were given in (atomics), which changes from frame to frame.
// LISTED_SOURCE (lpv_reflect_gathered_<format>_listed.comp, the third bounce): the light comes
// from the previous bounce's listed faces instead of the VPLs, each a square of a cell's side:
// cell c sums the faces of its own phase's list, times 16, but those of the 27 cells around it,
// which it sums whole (as vpl_gather.frag does for a pixel), and counts a face's r^2 plus its area
// over pi (a disk's form factor on its axis: at most its radiosity however near).
// Included by the generated lpv_reflect_gathered_<format>[_listed].comp (INJECT_FORMAT: the
// injection volume's).
#include "listed_faces.glsl"
#include "surface_areas.glsl"
#include "lpv_common.glsl"

#include "vpl.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, std140) uniform ReflectGathered {
    vec4 gridOrigin; // xyz: corner of cell 0, w: cell size
    ivec4 grid;      // x: cells per axis, y: 1 adds to the injection volume and the list, z: 1 marched,
                     // w: LISTED_SOURCE, the source list's counters (0 or 1)
    vec4 params;     // x: gi.intensity (1 for a listed source, whose flux holds it), y: the nearest
                     // a VPL counts (m^2 of r^2; LISTED_SOURCE: added to r^2), z: a face's share
                     // per area sample (0: no areas), w: the areas' stamp
    ivec4 vpls;      // x: slots, y: the cluster grid's side (2 slots a cluster), z: each phase's
                     // room, w: the counters this frame (0 or 1)
} params;
// Storage images below kPortableStorageImageBindings (rhi/Shader.h), which every device has.
layout(binding = 1, INJECT_FORMAT) uniform image3D injectedRed;
layout(binding = 2, INJECT_FORMAT) uniform image3D injectedGreen;
layout(binding = 3, INJECT_FORMAT) uniform image3D injectedBlue;
// Per cell, written by the first dispatch: its blocking faces (bits 26-31, -x -y -z +x +y +z) and
// the slot of the first in its phase's list (bits 0-25); 0: none. The gather reads it to sum the
// faces near a pixel whole (vpl_gather.frag).
layout(binding = 6, r32ui) uniform uimage3D faceSlots;
#ifdef LISTED_SOURCE
// The previous bounce's list and its faces' slots (GatheredReflection::listed(), faceSlots()).
layout(binding = 4, std430) readonly buffer SourceVpls {
    uint sourceCounts[32];
    Vpl sourceListed[];
};
layout(binding = 9) uniform usampler3D sourceSlots;
#else
layout(binding = 4, std430) readonly buffer Vpls { Vpl vpls[]; };
#endif
// The second bounce's VPLs: counts[16 vpls.w + phase] counts the slots given in each phase's list
// (it may pass the room; faces past it are not listed); the first dispatch clears the other 16
// counters, which the next frame uses. Phase p's list starts at slot p x room.
layout(binding = 5, std430) buffer BounceVpls {
    uint counts[32];
    Vpl listed[];
};
layout(binding = 7) uniform sampler3D faceTransmittance; // xyz: the cell's -x, -y, -z faces
layout(binding = 8) uniform sampler3D surfelAlbedo;      // rgb: mean albedo of the cell's surfels
// The surfaces' samples on each face, (3 x + axis, y, z) the lower face along axis of cell (x, y,
// z), in the low 12 bits under the stamp of the pass that counted them (SurfaceVoxels::areas()):
// a face reflects at most the share of it a surface covers. The geometry volume's blocked share
// spreads a surface's rim over the faces of the cells around its corner, and the faces beyond the
// rim, where no surface is, reflected what reached them.
layout(binding = 10) uniform usampler3D surfaceAreas;
// The march goes through the same faces (the first less than half open blocks), not through the
// scene's surfaces as the pixels' gather does (gi/SurfaceVoxels.h): a reflecting cell is one the
// geometry volume puts in front of a surface, and the surfaces' faces, a rounding of their own,
// put a surface in front of a share of those cells' centres, which then received nothing (the
// three-bounce means 3-6% lower, docs/gi-fidelity.md).
// The geometry volume's faces hold no plane: a blocked face blocks every segment through it.
bool faceBlocked(ivec3 c, int axis, vec2 span) { return texelFetch(faceTransmittance, c, 0)[axis] < 0.5; }
#include "vpl_visibility.glsl"

// The share of face f of cell c (-x -y -z +x +y +z) that a surface covers: the most of the
// faces within one of it along its axis. The geometry volume rounds a surface to a face along
// the axis as its surfels fall, and a surface near a cell's centre falls on both faces around it
// (the camera's marks keep the larger |n|): which one holds its area is the volume's to say, how
// much of the face's plane it covers the areas'. 1 beyond the volume.
float coveredShare(ivec3 c, int f) {
    const int axis = f % 3, n = params.grid.x;
    ivec3 q = c;
    if (f >= 3) q[axis] += 1;
    if (q[axis] >= n) return 1.0;
    uint samples = 0u;
    for (int k = max(q[axis] - 1, 0); k <= min(q[axis] + 1, n - 1); ++k) {
        ivec3 r = q;
        r[axis] = k;
        const uint area = texelFetch(surfaceAreas, ivec3(3 * r.x + axis, r.y, r.z), 0).x;
        if ((area >> kAreaCountBits) == uint(params.params.w)) samples = max(samples, area & kAreaCountMask);
    }
    return float(samples) * params.params.z;
}

// Below this blocked share a face reflects nothing (the slivers at a surface's rim).
const float kLeastBlocked = 0.02;

// Each face of `mask` of the cell at `centre` receives `weight` x what VPL v sends it (flux x cos x
// cos / r^2; pi is applied once by the caller).
void receive(Vpl v, float weight, uint mask, vec3 centre, inout vec3 e[6]) {
    const float cell = params.gridOrigin.w;
    // Where its light starts, as the injection places it: half a cell in front.
    const vec3 front = v.position.xyz + 0.5 * cell * v.normal.xyz;
    float visible = -1.0; // marched once, when a face first needs it
    for (int f = 0; f < 6; ++f) {
        if ((mask & (1u << f)) == 0u) continue;
        vec3 toward = vec3(0.0);
        toward[f % 3] = f < 3 ? -1.0 : 1.0;
        // The face's centre; its surfels face back into the cell, along -toward.
        const vec3 face = centre + 0.5 * cell * toward;
        const vec3 d = v.position.xyz - face;
        const float r2 = dot(d, d);
        const vec3 dir = d * inversesqrt(max(r2, 1e-12));
        const float w = max(-dot(toward, dir), 0.0) * max(dot(v.normal.xyz, -dir), 0.0);
        // A surface's coverage closes the faces on both sides of it; the face on its back, within
        // half a cell, would read its own VPLs' light as arriving.
        if (w <= 0.0 || dot(front - face, toward) >= 0.0) continue;
        if (visible < 0.0)
            visible = params.grid.z != 0 ? faceVisibility(params.gridOrigin, params.grid.x, centre,
                                                           v.position.xyz + kSurfaceLift * cell * v.normal.xyz)
                                         : 1.0;
#ifdef LISTED_SOURCE
        const float r2Counted = r2 + params.params.y;
#else
        const float r2Counted = max(r2, params.params.y);
#endif
        e[f] += v.flux.rgb * (weight * visible * w / r2Counted);
    }
}

void main() {
    const ivec3 c = ivec3(gl_GlobalInvocationID);
    const int n = params.grid.x;
    if (any(greaterThanEqual(c, ivec3(n)))) return;
    const bool adding = params.grid.y != 0;
    vec4 outR = vec4(0.0), outG = vec4(0.0), outB = vec4(0.0);
    if (adding) {
        outR = imageLoad(injectedRed, c);
        outG = imageLoad(injectedGreen, c);
        outB = imageLoad(injectedBlue, c);
    }
    // The blocked share of the faces: -x, -y, -z (the cell's own), then +x, +y, +z (the next
    // cells' lower faces; beyond the volume nothing blocks).
    const vec3 lower = vec3(1.0) - texelFetch(faceTransmittance, c, 0).xyz;
    const vec3 upper = vec3(1.0) - vec3(c.x + 1 < n ? texelFetch(faceTransmittance, c + ivec3(1, 0, 0), 0).x : 1.0,
                                        c.y + 1 < n ? texelFetch(faceTransmittance, c + ivec3(0, 1, 0), 0).y : 1.0,
                                        c.z + 1 < n ? texelFetch(faceTransmittance, c + ivec3(0, 0, 1), 0).z : 1.0);
    float blocked[6] = float[6](lower.x, lower.y, lower.z, upper.x, upper.y, upper.z);
    const vec3 albedo = texelFetch(surfelAlbedo, c, 0).rgb;
    uint mask = 0u;
    if (max(max(albedo.r, albedo.g), albedo.b) > 0.0)
        for (int f = 0; f < 6; ++f) {
            if (params.params.z > 0.0 && blocked[f] > kLeastBlocked)
                blocked[f] = min(blocked[f], coveredShare(c, f));
            if (blocked[f] > kLeastBlocked) mask |= 1u << f;
        }
    uint base = 0u;
    bool listedHere = false;
    const int phase = facePhase(c);
    const uint room = uint(params.vpls.z);
    if (!adding) {
        if (c.x < 16 && c.y == 0 && c.z == 0) counts[16 * (1 - params.vpls.w) + c.x] = 0u;
        if (mask != 0u) base = atomicAdd(counts[16 * params.vpls.w + phase], uint(bitCount(mask)));
        // A cell whose faces pass the room is not listed (its light still propagates).
        listedHere = mask != 0u && base + uint(bitCount(mask)) <= room;
        imageStore(faceSlots, c, uvec4(listedHere ? packListedSlots(mask, base) : 0u));
    } else {
        const uint slots = imageLoad(faceSlots, c).x;
        listedHere = listedFaceCount(slots) != 0u;
        base = firstListedSlot(slots);
    }
    if (mask != 0u) {
        const float cell = params.gridOrigin.w;
        const vec3 centre = params.gridOrigin.xyz + (vec3(c) + 0.5) * cell;
        vec3 e[6];
        for (int f = 0; f < 6; ++f)
            e[f] = vec3(0.0);
#ifdef LISTED_SOURCE
        // The faces of the 27 cells around whole; the rest, one phase's list times 16.
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const ivec3 q = c + ivec3(dx, dy, dz);
                    if (any(lessThan(q, ivec3(0))) || any(greaterThanEqual(q, ivec3(n)))) continue;
                    const uint slots = texelFetch(sourceSlots, q, 0).x;
                    const uint at = listedAt(q, slots, room);
                    for (uint i = 0u; i < listedFaceCount(slots); ++i)
                        receive(sourceListed[at + i], 1.0, mask, centre, e);
                }
        const uint count = min(sourceCounts[16 * params.grid.w + phase], room);
        for (uint i = 0u; i < count; ++i) {
            Vpl v = sourceListed[uint(phase) * room + i];
            const ivec3 q = listedFaceCell(v.position.xyz, v.normal.xyz, params.gridOrigin);
            if (any(greaterThan(abs(q - c), ivec3(1)))) receive(v, 16.0, mask, centre, e);
        }
#else
        const int side = params.vpls.y;
        const ivec2 first = ivec2((c.x + c.y) & 1, (c.y + c.z) & 1); // of the clusters it sums
        for (int cy = first.y; cy < side; cy += 2)
            for (int cx = first.x; cx < side; cx += 2)
                for (int layer = 0; layer < 2; ++layer) {
                    Vpl v = vpls[2 * (cy * side + cx) + layer];
                    if (v.position.w > 0.0) receive(v, 4.0, mask, centre, e); // the interleave's 4
                }
#endif
        // Irradiance (1 / pi) x the face's area is the flux received; a VPL's lobe is flux / pi
        // (inject.frag).
        const float toFlux = params.params.x / PI * cell * cell;
        for (int f = 0; f < 6; ++f) {
            if ((mask & (1u << f)) == 0u) continue;
            vec3 toward = vec3(0.0);
            toward[f % 3] = f < 3 ? -1.0 : 1.0;
            const vec3 reflected = albedo * blocked[f] * e[f] * toFlux;
            const uint slot = base + uint(bitCount(mask & ((1u << f) - 1u)));
            if (listedHere) {
                const uint at = uint(phase) * room + slot;
                vec3 sum = reflected;
                if (adding) sum += listed[at].flux.rgb;
                listed[at] = Vpl(vec4(centre + 0.5 * cell * toward, 1.0), vec4(-toward, 0.0), vec4(sum, 0.0));
            }
            const vec4 lobe = shCosineLobe(-toward) * (1.0 / PI);
            outR += reflected.r * lobe, outG += reflected.g * lobe, outB += reflected.b * lobe;
        }
    }
    imageStore(injectedRed, c, outR);
    imageStore(injectedGreen, c, outG);
    imageStore(injectedBlue, c, outB);
}
