#version 450
#extension GL_GOOGLE_include_directive : require
// The first bounce gathered per lookup texel from one set of VPLs (gi.gather, gi/VplGather.h):
// irradiance E = sum of flux x cos(at the VPL) x cos(at the receiver) / (pi r^2), the reflective
// shadow map's gather (Dachsbacher & Stamminger 2005), near a cluster the form factor of the patch
// it clusters (patch_form_factor.glsl), in the share of the lookup that the gathered
// cascades answer for. Interleaved: texel (x, y) of each 4 x 4 block sums the VPL clusters
// whose grid coordinates are (x, y) mod 4, times 16, so every block covers every cluster once; the
// lookup averages each block on its surface (lpv_lookup.glsl, GATHER).
//
// Which VPLs light which share: the sun's, in the gathered cascades' shares together, from the
// finest cascade whose box holds them (main); a spot or point light's, injected into each cascade
// they reach, in those cascades' shares.
#include "cascade_region.glsl"
#include "gathered_cascades.glsl"
#include "listed_faces.glsl"
#include "lpv_common.glsl"
#include "patch_form_factor.glsl"
#include "surface_faces.glsl"

#include "vpl.glsl"

layout(binding = 0, std140) uniform Gather {
    mat4 invViewProjection;
    vec4 gridOrigin[GATHERED_CASCADES]; // the finest cascades: xyz corner of cell 0, w cell size
    ivec4 grid;         // x: cells per axis, y: cascades in all, z: the sun's VPLs of cascade z,
                        // or -1: a light's, in the shares of cascades w (bit c)
    vec4 params;        // x: gi.intensity, y: blend band, z: the nearest a VPL counts (m^2 of r^2),
                        // w: 1 marched through the faces of cascade vpls.z, 0 unmarched
    ivec4 vpls;         // x: slots, y: the cluster grid's side (2 slots a cluster), z: the faces'
                        // cascade, w: 1 the VPLs are bounceVpls' lists (GatheredReflection), x
                        // each one's room, y their counters
    ivec4 pixels;       // x: resolution divisor, yz: G-buffer size, w: 0 (MUL_COLUMNS_AT)
    uvec4 faces;        // x: the stamp of cascade vpls.z's surfaces (gi/SurfaceVoxels.h)
    mat4 lightViewProjection; // the RSM's the VPLs were clustered from; zero: none
    ivec4 windows;      // x: 1 the sun's VPLs listed by window (binding 7), y: a list's room
} gather;
layout(binding = 1, std430) readonly buffer Vpls { Vpl vpls[]; };
// The second bounce's VPLs, where vpls.w is 1 (lpv_reflect_gathered_body.glsl): 16 lists of room
// vpls.x, by the phase of their cell; counts[16 vpls.y + phase] listed in each.
layout(binding = 5, std430) readonly buffer BounceVpls {
    uint counts[32];
    Vpl listed[];
} bounceVpls;
// Where vpls.w is 1: per cell of cascade vpls.z its listed faces (bits 26-31) and the slot of the
// first in its phase's list (lpv_reflect_gathered_body.glsl).
layout(binding = 6) uniform usampler3D faceSlots;
// Where windows.x is 1: the sun's lit VPLs each window takes, listed per phase in the grid's order
// (vpl_windows.comp): counts[16 window + phase], the list at slots[(16 window + phase) room].
layout(binding = 7, std430) readonly buffer Windows {
    uint counts[32];
    uint slots[];
} windows;
layout(binding = 2) uniform sampler2D depthTexture;
layout(binding = 3) uniform sampler2D normalTexture;
// Where params.w is 1: the faces the scene's surfaces cross, of cascade vpls.z, at texels
// (3 x + axis, y, z), blocked where a surface marked them with stamp faces.x and the segment
// crosses it (gi/SurfaceVoxels.h). Read as a storage image: a CPU rasterizer fetches an integer
// texture through a sampler several times slower.
layout(binding = 4, r32ui) uniform readonly uimage3D surfaceFaces;
bool faceBlocked(ivec3 c, int axis, vec2 span) {
    return surfaceCrossed(imageLoad(surfaceFaces, ivec3(3 * c.x + axis, c.y, c.z)).x, gather.faces.x, c[axis], span);
}
#include "vpl_visibility.glsl"

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outIrradiance;

bool inVolume(int c, vec3 p) {
    vec3 uvw = uvwInVolume(gather.gridOrigin[c], gather.grid.x, p);
    return all(greaterThanEqual(uvw, vec3(0.0))) && all(lessThanEqual(uvw, vec3(1.0)));
}

// The gathered cascades' shares of the lookup's answer at p, as lpv_lookup.glsl blends them: each
// takes its blend weight of what the finer ones leave (all of it when it is the coarsest); 0
// outside, and for a cascade that does not exist.
float[GATHERED_CASCADES] sharesAt(vec3 p) {
    float shares[GATHERED_CASCADES];
    float left = 1.0;
    for (int k = 0; k < GATHERED_CASCADES; ++k) {
        float inside = cascadeInsideness(gather.gridOrigin[k], gather.grid.x, gather.params.y, p);
        float w = k + 1 >= gather.grid.y ? (inVolume(k, p) ? 1.0 : 0.0) : smoothstep(0.0, 1.0, clamp(inside, 0.0, 1.0));
        shares[k] = k < gather.grid.y ? left * w : 0.0;
        left *= 1.0 - w;
    }
    return shares;
}

// Which of a set's VPLs light a texel, and in what share: those in the box of cascade `within`
// (-1: any) and not in the box of cascade `beyond` (-1: none).
struct Window {
    float share;
    int within;
    int beyond;
};

// Whether the surface point b (normal nb) sees the surface point a (normal na).
float visibility(vec3 a, vec3 na, vec3 b, vec3 nb) {
    return surfaceVisibility(gather.gridOrigin[gather.vpls.z], gather.grid.x, a, na, b, nb);
}

// What VPL v sends the surface at p with normal n, in its share of the lookup where the window
// takes it (main). Flux x cos x cos / r^2 (pi and the interleave's 16 are applied once in main).
vec3 fromVpl(Vpl v, vec3 p, vec3 n, float nearest, Window window) {
    // Without boxes (a light's VPLs, the listed faces), no test on the hottest loop.
    if (window.within >= 0 && !inVolume(window.within, v.position.xyz)) return vec3(0.0);
    if (window.beyond >= 0 && inVolume(window.beyond, v.position.xyz)) return vec3(0.0);
    float share = window.share;
    vec3 d = v.position.xyz - p;
    float r2 = dot(d, d);
    vec3 dir = d * inversesqrt(max(r2, 1e-12));
    float w = step(1e-30, v.position.w) * max(dot(v.normal.xyz, -dir), 0.0) * max(dot(n, dir), 0.0);
    // A cluster near its patch (the rectangle vpl_cluster.comp measured) counts as the patch: flux
    // / area x the patch's form factor x pi (patch_form_factor.glsl). Farther, or without a patch,
    // a point, its r^2 clamped at `nearest` (about its area).
    bool listed = gather.vpls.w != 0;
    vec2 e = patchExtents(v.position.w);
    bool patch_ = !listed && nearPatch(r2, e);
    if (patch_) w = patchFormFactor(p, n, v.position.xyz, v.normal.xyz, e);
    if (w > 0.0 && gather.params.w != 0.0) w *= visibility(p, n, v.position.xyz, v.normal.xyz);
    if (patch_) return v.flux.rgb * (share * w * PI / (4.0 * e.x * e.y));
    // A listed face (vpls.w 1) is a square of a cell's side on a cell's face, where no surface
    // need be: a disk of its area gives flux / (pi (r^2 + area / pi)) on its axis, at most its
    // radiosity however near (`nearest` is area / pi). Its exact square's form factor lit the
    // faces next to it more than the truth (docs/gi-fidelity.md).
    return v.flux.rgb * (share * w / (listed ? r2 + nearest : max(r2, nearest)));
}

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    ivec2 source = min(texel * gather.pixels.x, gather.pixels.yz - 1);
    float depth = texelFetch(depthTexture, source, 0).r;
    outIrradiance = vec4(0.0);
    if (depth >= 1.0) return;
    vec2 uv = (vec2(source) + 0.5) / vec2(gather.pixels.yz);
    vec4 world = MUL_COLUMNS_AT(gather.invViewProjection, gather.pixels.w, vec4(uv * 2.0 - 1.0, depth, 1.0));
    vec3 p = world.xyz / world.w;
    vec3 n = normalize(texelFetch(normalTexture, source, 0).xyz);

    float shares[GATHERED_CASCADES] = sharesAt(p);
    int k = gather.grid.z;
    Window window = Window(0.0, -1, -1);
    int home = GATHERED_CASCADES;
    if (k < 0) {
        for (int c = 0; c < GATHERED_CASCADES; ++c)
            if ((gather.grid.w & (1 << c)) != 0) window.share += shares[c];
    } else if (gather.vpls.w == 0) {
        // The sun's VPLs of cascade k: each surface's light comes once, from the finest cascade
        // whose box holds it, in all the gathered cascades' shares of a receiver in the finest
        // cascade that holds the receiver (`home`). A cascade's VPLs beyond its box (its light's
        // map reaches past it) would be marched through faces that end at the box, open beyond,
        // and let the sunlit ground through the doorway's walls; the next's within it have 4
        // times the area and faces twice the size. The coarsest gathered takes all of its own.
        float all_ = 0.0;
        for (int c = GATHERED_CASCADES - 1; c >= 0; --c) {
            if (shares[c] > 0.0) home = c;
            all_ += shares[c];
        }
        int last = min(gather.grid.y, GATHERED_CASCADES) - 1;
        if (k >= home && k <= last) window = Window(all_, k < last ? k : -1, k > home ? k - 1 : -1);
    }
    if (window.share <= 0.0) return;

    // A VPL stands for its cluster's patch: nearer than about its size, 1 / r^2 would count the
    // patch's light as a point's and blow up next to it.
    float nearest = gather.params.z;
    float half_ = 0.5 * gather.gridOrigin[gather.vpls.z].w;
    ivec2 phase = texel & 3;
    vec3 e = vec3(0.0);
    if (gather.vpls.w != 0) {
        // The faces of the 3 x 3 x 3 cells around the one in front of the texel, each texel all of
        // them: one phase's nearest face, times 16, would stand out of its block as a patch.
        vec4 o = gather.gridOrigin[gather.vpls.z];
        int cells = gather.grid.x;
        uint room = uint(gather.vpls.x);
        ivec3 home = ivec3(floor((p + half_ * n - o.xyz) / o.w));
        vec3 near = vec3(0.0);
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec3 c = home + ivec3(dx, dy, dz);
                    if (any(lessThan(c, ivec3(0))) || any(greaterThanEqual(c, ivec3(cells)))) continue;
                    uint slots = texelFetch(faceSlots, c, 0).x;
                    uint at = listedAt(c, slots, room);
                    for (uint i = 0u; i < listedFaceCount(slots); ++i)
                        near += fromVpl(bounceVpls.listed[at + i], p, n, nearest, window);
                }
        // The rest: texel (x, y) of each block sums the faces of the cells of one phase, whichever
        // order they were listed in.
        int k = phase.x + 4 * phase.y;
        uint start = uint(k) * room;
        uint count = min(bounceVpls.counts[16 * gather.vpls.y + k], room);
        for (uint i = 0u; i < count; ++i) {
            Vpl v = bounceVpls.listed[start + i];
            ivec3 c = listedFaceCell(v.position.xyz, v.normal.xyz, o);
            if (any(greaterThan(abs(c - home), ivec3(1)))) e += fromVpl(v, p, n, nearest, window);
        }
        e += near / 16.0;
    } else {
        // The clusters over the texel's own point of the light's map and next to it, each texel
        // all of them: the near field's light comes from a few, and where its 4 x 4 block lies
        // partly on another surface (a crease), the texels that would sum them in their phase are
        // left out of the block's average (lpv_lookup.glsl) and the pixel got next to nothing.
        int side = gather.vpls.y;
        vec4 light = MUL_COLUMNS_AT(gather.lightViewProjection, gather.pixels.w, vec4(p, 1.0));
        ivec2 own = ivec2(-8);
        if (light.w > 0.0) own = ivec2(floor((light.xy / light.w * 0.5 + 0.5) * float(side)));
        vec3 near = vec3(0.0);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                ivec2 c = own + ivec2(dx, dy);
                if (any(lessThan(c, ivec2(0))) || any(greaterThanEqual(c, ivec2(side)))) continue;
                for (int layer = 0; layer < 2; ++layer)
                    near += fromVpl(vpls[2 * (c.y * side + c.x) + layer], p, n, nearest, window);
            }
        if (gather.windows.x != 0) {
            // The lit VPLs of the texel's window (vpl_windows.comp), in the grid's order.
            int list = 16 * (k > home ? 1 : 0) + phase.x + 4 * phase.y;
            uint start = uint(list * gather.windows.y);
            uint count = windows.counts[list];
            for (uint i = 0u; i < count; ++i) {
                uint slot = windows.slots[start + i];
                int cluster = int(slot >> 1);
                if (all(lessThanEqual(abs(ivec2(cluster % side, cluster / side) - own), ivec2(1)))) continue;
                e += fromVpl(vpls[slot], p, n, nearest, window);
            }
        } else {
            for (int cy = phase.y; cy < side; cy += 4)
                for (int cx = phase.x; cx < side; cx += 4) {
                    if (all(lessThanEqual(abs(ivec2(cx, cy) - own), ivec2(1)))) continue;
                    for (int layer = 0; layer < 2; ++layer)
                        e += fromVpl(vpls[2 * (cy * side + cx) + layer], p, n, nearest, window);
                }
        }
        e += near / 16.0;
    }
    outIrradiance = vec4(e * (gather.params.x * 16.0 / PI), 0.0);
}
