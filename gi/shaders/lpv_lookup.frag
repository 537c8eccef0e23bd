#version 450
#extension GL_GOOGLE_include_directive : require
// Indirect irradiance from the accumulated LPV: a trilinear lookup half a cell along the normal,
// the SH intensity integrated against the clamped cosine of the incoming directions, divided by
// the cell's cross-section to turn intensity into radiance. Anisotropic damping: when the field
// grows into the surface (light that arrives from behind it, through the wall), the lookup is
// scaled down by the relative directional derivative along the normal.
#include "lpv_common.glsl"

layout(binding = 0, std140) uniform Lookup {
    mat4 invViewProjection;
    vec4 gridOrigin;  // xyz: corner of cell 0, w: cell size
    ivec4 grid;       // x: cells per axis, y: volumes are rgba8-encoded, z: damping on
    vec4 encode;      // x: rgba8 range
    vec4 intensity;   // x: gi.intensity (already applied at injection), y: damping strength
} lookup;
layout(binding = 1) uniform sampler2D depthTexture;
layout(binding = 2) uniform sampler2D normalTexture;
layout(binding = 3) uniform sampler3D lpvRed;
layout(binding = 4) uniform sampler3D lpvGreen;
layout(binding = 5) uniform sampler3D lpvBlue;

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outIrradiance;

vec4 decode(vec4 v) { return lookup.grid.y != 0 ? (v * 2.0 - 1.0) * lookup.encode.x : v; }

vec3 irradianceAt(vec3 p, vec3 n) {
    float extent = lookup.gridOrigin.w * float(lookup.grid.x);
    vec3 uvw = (p - lookup.gridOrigin.xyz) / extent;
    if (any(lessThan(uvw, vec3(0.0))) || any(greaterThan(uvw, vec3(1.0)))) return vec3(0.0);
    // Incoming light travels against n: integrate against the lobe around -n.
    vec4 lobe = shCosineLobe(-n);
    vec3 e = vec3(dot(decode(texture(lpvRed, uvw)), lobe), dot(decode(texture(lpvGreen, uvw)), lobe),
                  dot(decode(texture(lpvBlue, uvw)), lobe));
    float area = lookup.gridOrigin.w * lookup.gridOrigin.w;
    return max(e, vec3(0.0)) / area;
}

void main() {
    float depth = textureLod(depthTexture, vUv, 0.0).r;
    if (depth >= 1.0) {
        outIrradiance = vec4(0.0);
        return;
    }
    vec4 clip = vec4(vUv * 2.0 - 1.0, depth, 1.0);
    vec4 world = lookup.invViewProjection * clip;
    vec3 p = world.xyz / world.w;
    vec3 n = normalize(textureLod(normalTexture, vUv, 0.0).xyz);
    float cell = lookup.gridOrigin.w;
    vec3 front = irradianceAt(p + 0.5 * cell * n, n);
    vec3 e = front;
    if (lookup.grid.z != 0) {
        vec3 behind = irradianceAt(p - 0.5 * cell * n, n);
        float f = dot(front, vec3(0.2126, 0.7152, 0.0722));
        float bk = dot(behind, vec3(0.2126, 0.7152, 0.0722));
        float growth = max(bk - f, 0.0) / max(bk, 1e-6);
        e *= clamp(1.0 - lookup.intensity.y * growth, 0.0, 1.0);
    }
    outIrradiance = vec4(e, 0.0);
}
