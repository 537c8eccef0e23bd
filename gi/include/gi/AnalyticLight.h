// Point and spot lights added to the LPV analytically, already propagated (Kaplanyan 2009, "massive
// lighting", option 2): no RSM, no injection, no propagation error. This header holds the light as
// the GPU pass reads it and the formula on the CPU, which the tests compare the GPU volume with;
// gi/shaders/point_lights_body.glsl evaluates the same formula per cell.
//
// The formula, per light and cell, per colour channel:
//
//   sh += g * I * spot(w) * window(d) * (s^2 / d^2) / pi * cosLobe(w)
//
//   p: light position, x: cell centre, d = |x - p|, w = (x - p) / d (the direction light travels),
//   I: radiant intensity, colour x intensity (candela: W/sr in the units the renderer lights with),
//   s: cell size, g: gi.intensity (the same scale the VPLs get at injection),
//   spot(w) = smoothstep(cos outer, cos inner, dot(w, spot direction)), 1 for point lights,
//   window(d) = clamp(1 - (d / range)^4, 0, 1), 1 for an infinite range
//   (spot and window are the renderer's, engine/shaders/lighting.frag, so both agree on a light).
//
// Why: a cell of the volume stores radiant intensity whose L1 SH divided by the cell's
// cross-section s^2 is the radiance the lookup integrates (gi/shaders/lpv_lookup.frag). Seen from
// the light, a cell's cross-section subtends s^2 / d^2 sr, so the flux crossing it is
// phi = I * s^2 / d^2, all travelling along w. Injection and propagation store a flux phi as a
// clamped-cosine lobe of intensity phi / pi (a VPL of flux phi; a propagation face re-emitting
// the flux through it), whose L0 coefficient is phi / (2 sqrt(pi)), so this light's flux and a
// VPL's flux are the same coefficients in the volume: the analytic term is what an ideal,
// error-free propagation of a light of intensity I would leave in the accumulated volume (the
// shipped propagation spreads such a light sideways: the paper's propagation error). The
// lookup then gives a surface facing the light (c0^2 + c1^2) / pi = 0.583 of I / d^2 and a surface
// edge-on 0.25 of it: the L1 cosine-lobe blur every propagated light in the volume has.
//
// The cell that holds the light (its centre within half a cell of the light on every axis) gets
// nothing: there the light is isotropic (no direction of arrival) and d goes to 0. Every other
// cell's centre is at least half a cell from the light, so s^2 / d^2 <= 4 sr and nothing diverges.
#pragma once

#include "engine/scene/Scene.h"
#include "gi/LpvReference.h"

#include <glm/vec4.hpp>

#include <span>

namespace lpv::gi {

// std430 element of `Lights` in point_lights_body.glsl.
struct AnalyticLight {
    glm::vec4 positionInvRange2; // xyz: position; w: 1 / range^2, 0 for an infinite range
    glm::vec4 intensityCos; // rgb: radiant intensity per channel (W/sr) x gi.intensity; w: cos(outer cone)
    glm::vec4 spotCos;      // xyz: direction the spot light points; w: cos(inner cone)
};
static_assert(sizeof(AnalyticLight) == 48);

// A point or spot light as the pass reads it, scaled by `intensityScale` (gi.intensity). Point lights
// get a cone that lets every direction through.
AnalyticLight analyticLight(const engine::Light& light, float intensityScale);

// False when the light cannot reach any cell of the volume (its range sphere misses it) or is dark.
bool reachesVolume(const AnalyticLight& light, const VolumeGrid& grid);

// The SH the light adds to `cell` (the formula above), on the CPU.
ShCell analyticLightCell(const AnalyticLight& light, const VolumeGrid& grid, glm::ivec3 cell);

// Adds every light to every cell of `volume` (the CPU reference of the GPU pass).
void addAnalyticLightsReference(ShVolume& volume, const VolumeGrid& grid,
                                std::span<const AnalyticLight> lights);

} // namespace lpv::gi
