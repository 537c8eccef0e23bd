#version 450
#extension GL_GOOGLE_include_directive : require
// Spot RSM texel: world normal (facing the light) and reflected flux = diffuse albedo x the share
// the specular layer lets through (rsm_diffuse.glsl) x the flux the light
// sends through the texel: I x cone x range window x the texel's solid angle. That is the
// irradiance engine/shaders/lighting.frag gives the surface (I x cone x window / d^2 x cos) times
// the surface area the texel covers (solid angle x d^2 / cos), so a spot VPL and a sun VPL of the
// same reflected power carry the same flux. A texel of a perspective map subtends the axis texel's
// solid angle times cos^3 of its angle off the axis.
#include "rsm_diffuse.glsl"
#include "rsm_light_facing.glsl"
layout(binding = 0, std140) uniform SpotRsm {
    mat4 lightViewProjection;
    vec4 lightPosition;
    vec4 spotDirection;
    vec4 cone;
    vec4 intensity;
} rsm;
#include "draw_uniforms.glsl"
layout(binding = 2) uniform sampler2D baseColorTexture;
layout(binding = 4) uniform sampler2D metallicRoughnessTexture;

layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec2 vUv;
layout(location = 2) in vec3 vWorld;
layout(location = DRAW_INDEX_LOCATION) flat in uint vDrawIndex;
layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outFlux;

void main() {
    DrawRecord draw = drawRecords.draws[vDrawIndex];
    vec3 toSurface = vWorld - rsm.lightPosition.xyz;
    float d2 = max(dot(toSurface, toSurface), 1e-8);
    vec3 w = toSurface * inversesqrt(d2);
    vec3 n = normalize(vNormal);
    // Two-sided: the side the light sees; where a face turned toward it lies in the same plane,
    // that face.
    bool facesLight = dot(n, w) <= 0.0;
    writeLightFacingDepth(facesLight);
    if (!facesLight) n = -n;
    float cosAxis = max(dot(w, rsm.spotDirection.xyz), 0.0);
    float q = d2 * rsm.lightPosition.w;  // (d / range)^2
    float window = clamp(1.0 - q * q, 0.0, 1.0);
    float spot = smoothstep(rsm.cone.x, rsm.cone.y, cosAxis);
    float solidAngle = rsm.spotDirection.w * cosAxis * cosAxis * cosAxis;
    vec3 base = draw.baseColor.rgb;
    if (draw.material.w > 0.5) base *= texture(baseColorTexture, vUv).rgb;
    vec4 material = draw.material; // metallic as the G-buffer has it: the factor times the map's B
    if (draw.maps.x > 0.5) material.x *= texture(metallicRoughnessTexture, vUv).b;
    outNormal = vec4(n, 1.0);
    outFlux = vec4(diffuseReflectance(base, material, -dot(n, w)) * rsm.intensity.rgb *
                       (spot * window * solidAngle),
                   1.0);
}
