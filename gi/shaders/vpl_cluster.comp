#version 450
#extension GL_GOOGLE_include_directive : require
// VPL down-sampling: each thread clusters one block of RSM texels into VPLs, weighting position
// and normal by the texels' flux luminance (intensity-aware clustering) and summing the flux, so
// the total reflected flux is unchanged. A block that spans a depth edge (a roof's rim over the
// floor below, a box's top over the floor beside it) would average its surfaces into a point in
// mid air, whose light is no surface's (the atrium's indirect light came out 9% darker at the
// default VPL count than with a VPL per texel, and 36% off per pixel on average): such a block
// clusters its texels nearer the light and those farther into two VPLs, each on its surface.
// Every block has two slots (kVplsPerCluster); the second stays empty (w 0) without an edge.
// The per-pixel gather's VPLs (options.x, binding 5) split a crease (a box's top and side) the
// same way by normal, so each side lights its neighbours as its own surface, and keep to one
// plane a side (planeOf: a roof and a box's top below it made a VPL in mid air); the volume's
// keep a crease whole (split, they made the bounce taken from the frame before differ more from
// this frame's: docs/gi-fidelity.md).
// Each VPL also records its patch: the rectangle on its plane its texels cover, which the
// per-pixel gather takes for it near a receiver (patch_form_factor.glsl, vpl_gather.frag).
#include "lpv_common.glsl"
#include "patch_form_factor.glsl"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "vpl.glsl"

layout(binding = 0, std140) uniform Params {
    mat4 invLightViewProjection;
    ivec4 sizes;  // x: RSM size, y: VPL grid side, z: block side, w: 0 (see below)
    ivec4 options; // x: 1 writes the gather's VPLs too
} params;
layout(binding = 1) uniform sampler2D rsmDepth;
layout(binding = 2) uniform sampler2D rsmNormal;
layout(binding = 3) uniform sampler2D rsmFlux;
layout(binding = 4, std430) writeonly buffer Vpls {
    Vpl vpls[];
};
// Where options.x is 1: the gather's (vpl_gather.frag); else bound to the volume's, unwritten.
layout(binding = 5, std430) writeonly buffer GatherVpls {
    Vpl gatherVpls[];
};

// World position of the RSM's point t (texels) at `depth` (clip depth).
vec3 worldAtPoint(vec2 t, float depth) {
    // The matrix's columns at an index the compiler cannot fold (sizes.w is 0; MUL_COLUMNS_AT):
    // read at constant offsets, lavapipe recompiled this shader on every frame the sun moved
    // (90-130 ms per cascade with a cold shader cache, against 2 ms).
    const int col = params.sizes.w;
    vec4 clip = vec4(t / float(params.sizes.x) * 2.0 - 1.0, depth, 1.0);
    vec4 world = MUL_COLUMNS_AT(params.invLightViewProjection, col, clip);
    return world.xyz / world.w;
}

// World position of RSM texel t at `depth` (clip depth).
vec3 worldAt(ivec2 t, float depth) {
    return worldAtPoint(vec2(t) + 0.5, depth);
}

// The area texel t covers on its surface (normal n) at `depth`: its footprint on the plane of
// constant depth, carried along the texel's ray onto the surface, the cosine clamped as the
// geometry volume's surfels' (gv_vpl_body.glsl) so grazing texels do not explode.
float texelArea(ivec2 t, float depth, vec3 n, vec3 p) {
    vec2 centre = vec2(t) + 0.5;
    vec3 across = cross(worldAtPoint(centre + vec2(1.0, 0.0), depth) - p, worldAtPoint(centre + vec2(0.0, 1.0), depth) - p);
    vec3 ray = normalize(p - worldAtPoint(centre, 0.0));
    float a = length(across);
    return a * abs(dot(ray, across / max(a, 1e-30))) / max(abs(dot(ray, n)), 0.25);
}

// Whether a texel (normal n at p) lies on `plane` (xyz its normal, w its offset): turned less than
// 45 degrees from it, and at most `apart` off it.
bool onPlane(vec4 plane, vec3 n, vec3 p, float apart) {
    return dot(n, plane.xyz) >= 0.7071 && abs(dot(plane.xyz, p) - plane.w) <= apart;
}

// Whether a texel belongs to `layer`: beyond the middle depth (layer 1) or before it at an edge;
// for the gather's VPLs (`creases`) without an edge, turned from the first layer's plane or not.
bool inLayer(int layer, float depth, vec3 n, bool edge, float split, bool creases, vec4 plane0) {
    bool second = edge || !creases ? depth > split : dot(n, plane0.xyz) < 0.7071;
    return second == (layer == 1);
}

// The plane of `layer` of the gather's VPLs: its brightest texel's, or where its texels facing
// that way but more than `apart` off it hold more flux than those on it (a roof over a box's top),
// the brightest of those's. Without an edge, layer 0 chooses among all the block's texels (the
// others turn from its plane: layer 1). `mixed`: set where a texel lies off its layer's plane.
vec4 planeOf(ivec2 first, int block, bool edge, float split, vec4 plane0, int layer, float apart, inout bool mixed) {
    vec4 plane = vec4(0.0, 1.0, 0.0, 0.0), other = plane;
    float brightest = -1.0, on = 0.0, brightestOff = -1.0, onOther = 0.0;
    for (int pass = 0; pass < 3; ++pass) {
        for (int y = 0; y < block; ++y)
            for (int x = 0; x < block; ++x) {
                ivec2 t = first + ivec2(x, y);
                float depth = texelFetch(rsmDepth, t, 0).r;
                if (depth >= 1.0) continue;
                vec3 n = normalize(texelFetch(rsmNormal, t, 0).xyz);
                if (!(layer == 0 && !edge) && !inLayer(layer, depth, n, edge, split, true, plane0)) continue;
                vec3 p = worldAt(t, depth);
                float l = dot(texelFetch(rsmFlux, t, 0).rgb, vec3(0.2126, 0.7152, 0.0722));
                if (pass == 0 && l > brightest) {
                    brightest = l;
                    plane = vec4(n, dot(n, p));
                } else if (pass == 1 && onPlane(plane, n, p, apart)) {
                    on += l;
                } else if (pass == 1) {
                    mixed = true;
                    if (dot(n, plane.xyz) >= 0.7071 && l > brightestOff) {
                        brightestOff = l;
                        other = vec4(n, dot(n, p));
                    }
                } else if (pass == 2 && onPlane(other, n, p, apart)) {
                    onOther += l;
                }
            }
        if ((pass == 0 && brightest < 0.0) || (pass == 1 && brightestOff < 0.0)) break;
    }
    return onOther > on ? other : plane;
}

// The VPL of `layer` of the block at `first`: its texels' flux, their flux-weighted position and
// normal, and the patch they cover (inLayer). With `creases` (the gather's VPLs), only the texels
// on their layer's plane (`planes`, planeOf) shape it; the others (a roof's rim by its top, a
// box's top below a roof on one side of an edge) add their flux: averaged in, the VPL would face
// neither way, or hang in mid air between the two, where a receiver next to it (a ceiling over
// the box) takes its light as arriving from in front.
Vpl clustered(ivec2 first, int block, bool edge, float split, bool creases, vec4 planes[2], float apart, int layer) {
    vec3 position = vec3(0.0), normal = vec3(0.0), flux = vec3(0.0);
    float weight = 0.0, texels = 0.0, area = 0.0, shaping = 0.0;
    vec2 patch_ = vec2(0.0);
    for (int pass = 0; pass < 2; ++pass) {
        // Pass 0 sums the texels; pass 1, given the VPL's centre and plane, the rectangle around
        // the centre that holds their footprints (the patch a receiver near it sees).
        vec3 centre = position / max(weight, 1e-30), m = normalize(normal);
        vec3 tangent = patchTangent(m), bitangent = cross(m, tangent);
        vec2 lo = vec2(0.0), hi = vec2(0.0); // the texels' extents on each side of the centre
        float off = 0.0;                     // the farthest a texel lies off the plane
        for (int y = 0; y < block; ++y)
            for (int x = 0; x < block; ++x) {
                ivec2 t = first + ivec2(x, y);
                float depth = texelFetch(rsmDepth, t, 0).r;
                if (depth >= 1.0) continue;
                // The volume's VPLs fetch a texel's normal only where they sum it.
                vec3 n = creases ? normalize(texelFetch(rsmNormal, t, 0).xyz) : vec3(0.0);
                if (!inLayer(layer, depth, n, edge, split, creases, planes[0])) continue;
                vec3 p = worldAt(t, depth);
                bool shapes = !creases || onPlane(planes[layer], n, p, apart);
                if (pass == 1) {
                    if (!shapes) continue;
                    vec2 q = vec2(dot(p - centre, tangent), dot(p - centre, bitangent));
                    lo = max(lo, -q);
                    hi = max(hi, q);
                    off = max(off, abs(dot(p - centre, m)));
                    continue;
                }
                if (!creases) n = normalize(texelFetch(rsmNormal, t, 0).xyz);
                vec3 f = texelFetch(rsmFlux, t, 0).rgb;
                flux += f;
                texels += 1.0;
                if (!shapes) continue;
                float w = dot(f, vec3(0.2126, 0.7152, 0.0722)) + 1e-8;
                position += w * p;
                normal += w * n;
                weight += w;
                area += texelArea(t, depth, n, p);
                shaping += 1.0;
            }
        if (weight <= 0.0) break;
        if (pass == 1) {
            // Texels turned apart (a box's top and side, without `creases`), or apart along the
            // normal (a roof and a box's top below it on one side of a depth edge), make no plane:
            // a point then (extents nil).
            bool flat_ = length(normal) > 0.9 * weight && off <= 0.2 * max(max(lo.x, hi.x), max(lo.y, hi.y));
            // Centred on the VPL, the rectangle reaches as far as the texels on its nearer side:
            // one reaching their farther side would hang past the surface's edge, lit where a
            // receiver beyond the edge sees it. Its sides run along the world's axes
            // (patchTangent), a block's along the light's: for a block turned to them it holds up
            // to twice the block's area (shrunk to the texels' area, it left a gap at the foot of
            // a wall: docs/gi-fidelity.md).
            patch_ = flat_ ? min(lo, hi) + 0.5 * sqrt(area / shaping) : vec2(0.0);
        }
    }
    Vpl v;
    v.position = weight > 0.0 ? vec4(position / weight, packPatchExtents(patch_)) : vec4(0.0);
    v.normal = vec4(length(normal) > 0.0 ? normalize(normal) : vec3(0.0, 1.0, 0.0), texels / float(block * block));
    v.flux = vec4(flux, texels); // w: the texels it clusters (the geometry volume's albedo)
    return v;
}

void main() {
    ivec2 cluster = ivec2(gl_GlobalInvocationID.xy);
    int side = params.sizes.y;
    if (cluster.x >= side || cluster.y >= side) return;
    int block = params.sizes.z;
    ivec2 first = cluster * block;
    // The block's depth range, and the widest gap between two neighbouring texels.
    float nearest = 1.0, farthest = 0.0, gap = 0.0;
    for (int y = 0; y < block; ++y)
        for (int x = 0; x < block; ++x) {
            ivec2 t = first + ivec2(x, y);
            float depth = texelFetch(rsmDepth, t, 0).r;
            if (depth >= 1.0) continue;
            nearest = min(nearest, depth);
            farthest = max(farthest, depth);
            if (params.options.x == 0) continue; // the gather's VPLs alone split by the gaps
            vec3 p = worldAt(t, depth);
            for (int k = 0; k < 2; ++k) {
                ivec2 u = t + (k == 0 ? ivec2(1, 0) : ivec2(0, 1));
                if (u.x >= first.x + block || u.y >= first.y + block) continue;
                float d = texelFetch(rsmDepth, u, 0).r;
                if (d < 1.0) gap = max(gap, distance(p, worldAt(u, d)));
            }
        }
    // An edge, for the volume's VPLs: the nearest and farthest texels lie further apart along the
    // light than twice the block's side. Then the texels split at the middle depth; otherwise all
    // go to the first VPL.
    vec3 near = worldAt(first, nearest);
    float blockSide = distance(near, worldAt(first + ivec2(block, 0), nearest));
    bool edge = farthest > nearest && distance(near, worldAt(first, farthest)) > 2.0 * blockSide;
    float split = edge ? 0.5 * (nearest + farthest) : 2.0;
    // For the gather's: two neighbouring texels further apart than twice the block's side (a
    // roof's rim over the floor below). A wall lit at a grazing angle spans more depth in a block
    // than that, and taken for an edge the block over its foot put the wall's lowest texels in the
    // floor's VPL, which lights no floor: the floor at the wall's foot lit or not as the blocks
    // fell. The volume's keep the depth range: split by the gaps, they let more of a sunlit
    // outside into a sealed room (docs/gi-fidelity.md).
    bool gatherEdge = gap > 2.0 * blockSide;
    float gatherSplit = gatherEdge ? 0.5 * (nearest + farthest) : 2.0;
    const int slot = 2 * (cluster.y * side + cluster.x);
    vec4 planes[2] = vec4[2](vec4(0.0, 1.0, 0.0, 0.0), vec4(0.0, 1.0, 0.0, 0.0));
    // Off a surface's plane by more than a quarter of the block's side: another surface.
    const float apart = 0.25 * blockSide;
    Vpl volume[2];
    for (int layer = 0; layer < 2; ++layer) {
        volume[layer] = clustered(first, block, edge, split, false, planes, apart, layer);
        vpls[slot + layer] = volume[layer];
    }
    if (params.options.x == 0) return;
    // The gather's. A block whose texels all lie on their layer's plane, split as the volume's,
    // clusters as the volume's.
    bool mixed = gatherEdge != edge;
    planes[0] = planeOf(first, block, gatherEdge, gatherSplit, planes[0], 0, apart, mixed);
    planes[1] = planeOf(first, block, gatherEdge, gatherSplit, planes[0], 1, apart, mixed);
    for (int layer = 0; layer < 2; ++layer)
        gatherVpls[slot + layer] =
            mixed ? clustered(first, block, gatherEdge, gatherSplit, true, planes, apart, layer) : volume[layer];
}
