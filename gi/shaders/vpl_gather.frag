#version 450
#extension GL_GOOGLE_include_directive : require
// The first bounce gathered per lookup texel from one set of VPLs (gi.gather, gi/VplGather.h):
// irradiance E = sum of flux x cos(at the VPL) x cos(at the receiver) / (pi r^2), the reflective
// shadow map's gather (Dachsbacher & Stamminger 2005), in the share of the lookup that the two
// finest cascades answer for. Interleaved: texel (x, y) of each 4 x 4 block sums the VPL clusters
// whose grid coordinates are (x, y) mod 4, times 16, so every block covers every cluster once; the
// lookup averages each block on its surface (lpv_lookup.glsl, GATHER).
//
// Which VPLs light which share: the sun's VPLs of cascade c in cascade c's share; a spot or point
// light's, injected into each cascade they reach, in those cascades' shares. A cascade's
// propagated first bounce, which the lookup takes out, also holds the light the next coarser
// cascade handed in across its border: that light is lost (docs/gi-fidelity.md measures gathering
// the coarser cascade's VPLs outside the finer one instead: more light through the doorway's walls).
#include "cascade_region.glsl"
#include "lpv_common.glsl"

struct Vpl {
    vec4 position; // w: 1 when the cluster holds a lit texel
    vec4 normal;
    vec4 flux;
};

layout(binding = 0, std140) uniform Gather {
    mat4 invViewProjection;
    vec4 gridOrigin[2]; // the two finest cascades: xyz corner of cell 0, w cell size
    ivec4 grid;         // x: cells per axis, y: cascades in all, z: the sun's VPLs of cascade z,
                        // or -1: a light's, in the shares of cascades w (bit c)
    vec4 params;        // x: gi.intensity, y: blend band, z: the nearest a VPL counts (m^2 of r^2),
                        // w: 1 marched through the faces of cascade vpls.z, 0 unmarched
    ivec4 vpls;         // x: slots, y: the cluster grid's side (2 slots a cluster), z: the faces'
                        // cascade, w: 0
    ivec4 pixels;       // x: resolution divisor, yz: G-buffer size, w: 0 (MUL_COLUMNS_AT)
} gather;
layout(binding = 1, std430) readonly buffer Vpls { Vpl vpls[]; };
layout(binding = 2) uniform sampler2D depthTexture;
layout(binding = 3) uniform sampler2D normalTexture;
// The faces of cascade vpls.z (the transmittance of each cell's -x, -y, -z faces), where params.w
// is 1.
layout(binding = 4) uniform sampler3D faceTransmittance;

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outIrradiance;

bool inVolume(int c, vec3 p) {
    vec3 uvw = uvwInVolume(gather.gridOrigin[c], gather.grid.x, p);
    return all(greaterThanEqual(uvw, vec3(0.0))) && all(lessThanEqual(uvw, vec3(1.0)));
}

// The two finest cascades' shares of the lookup's answer at p, as lpv_lookup.glsl blends them:
// the finest takes its blend weight, the next what that leaves of its own (all of it when it is
// the coarsest); 0 outside.
vec2 sharesAt(vec3 p) {
    float w[2];
    for (int k = 0; k < 2; ++k) {
        float inside = cascadeInsideness(gather.gridOrigin[k], gather.grid.x, gather.params.y, p);
        w[k] = k + 1 >= gather.grid.y ? (inVolume(k, p) ? 1.0 : 0.0) : smoothstep(0.0, 1.0, clamp(inside, 0.0, 1.0));
    }
    return vec2(w[0], gather.grid.y > 1 ? (1.0 - w[0]) * w[1] : 0.0);
}

// Whether b sees a through the faces of cascade vpls.z (GeometryVolume): a 3D DDA over its cells,
// blocked by the first face less than half open. A face's transmittance is the share of it that
// surfels leave open; multiplied along the segment, the partly covered faces a path grazes along
// a surface darkened the Cornell box by a fifth (docs/gi-fidelity.md), while a wall is one surface
// that either stands in the way or not. A segment leaving the volume is open beyond it.
float visibility(vec3 a, vec3 b) {
    vec4 o = gather.gridOrigin[gather.vpls.z];
    int n = gather.grid.x;
    vec3 ta = (a - o.xyz) / o.w, tb = (b - o.xyz) / o.w;
    ivec3 c = ivec3(floor(ta));
    vec3 d = tb - ta;
    ivec3 st = ivec3(sign(d));
    vec3 inv = 1.0 / max(abs(d), vec3(1e-6));
    vec3 tMax = vec3(d.x > 0.0 ? float(c.x + 1) - ta.x : ta.x - float(c.x),
                     d.y > 0.0 ? float(c.y + 1) - ta.y : ta.y - float(c.y),
                     d.z > 0.0 ? float(c.z + 1) - ta.z : ta.z - float(c.z)) * inv;
    for (int i = 0; i < 3 * n; ++i) {
        int axis = tMax.x < tMax.y ? (tMax.x < tMax.z ? 0 : 2) : (tMax.y < tMax.z ? 1 : 2);
        if (tMax[axis] > 1.0) break;
        ivec3 upper = c;
        if (st[axis] > 0) upper[axis] += 1;
        if (any(lessThan(upper, ivec3(0))) || any(greaterThanEqual(upper, ivec3(n)))) break;
        if (texelFetch(faceTransmittance, upper, 0)[axis] < 0.5) return 0.0;
        c[axis] += st[axis];
        tMax[axis] += inv[axis];
    }
    return 1.0;
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

    vec2 shares = sharesAt(p);
    int k = gather.grid.z;
    float share = k == 0 ? shares.x : (k == 1 ? shares.y : 0.0);
    if (k < 0) share = ((gather.grid.w & 1) != 0 ? shares.x : 0.0) + ((gather.grid.w & 2) != 0 ? shares.y : 0.0);
    if (share <= 0.0) return;

    // A VPL stands for its cluster's patch: nearer than about its size, 1 / r^2 would count the
    // patch's light as a point's and blow up next to it.
    float nearest = gather.params.z;
    float half_ = 0.5 * gather.gridOrigin[gather.vpls.z].w;
    int side = gather.vpls.y;
    ivec2 phase = texel & 3;
    vec3 e = vec3(0.0);
    for (int cy = phase.y; cy < side; cy += 4)
        for (int cx = phase.x; cx < side; cx += 4)
            for (int layer = 0; layer < 2; ++layer) {
                Vpl v = vpls[2 * (cy * side + cx) + layer];
                vec3 d = v.position.xyz - p;
                float r2 = dot(d, d);
                vec3 dir = d * inversesqrt(max(r2, 1e-12));
                float w = step(0.5, v.position.w) * max(dot(v.normal.xyz, -dir), 0.0) * max(dot(n, dir), 0.0);
                // From half a cell in front of each surface, as the injection and lookup place
                // light, so neither end's own surface blocks it.
                if (w > 0.0 && gather.params.w != 0.0)
                    w *= visibility(p + half_ * n, v.position.xyz + half_ * v.normal.xyz);
                e += v.flux.rgb * (w / max(r2, nearest));
            }
    outIrradiance = vec4(e * (share * gather.params.x * 16.0 / PI), 0.0);
}
