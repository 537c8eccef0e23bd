// The 6-neighbour, 5-face propagation scheme of Kaplanyan & Dachsbacher (Cascaded LPV, I3D 2010),
// shared by the CPU reference and the GPU kernels (whose shader constants must match these).
//
// A destination cell gathers from each of its 6 neighbours. From the neighbour's centre, the
// destination cell shows 5 faces: the far face (normal along the neighbour-to-destination axis d)
// and 4 side faces. The flux through a face is the neighbour's intensity in the direction of the
// face's centre times the face's solid angle; it is re-emitted from the face as a clamped-cosine
// lobe along the face normal, i.e. a VPL of that flux (intensity = flux / pi * cos).
//
// The flux is not clamped at zero, so the step is linear in the SH coefficients: the five faces a
// neighbour on axis e lights sum to one sparse 4x4 matrix. With p the neighbour at cell - e and m
// the one at cell + e, coefficient index k of e's axis (x: 3, y: 1, z: 2) and the other two q:
//   out[0] += A (p0 + m0) + B (pk - mk)      out[k] += C (p0 - m0) + D (pk + mk)
//   out[q] += E (pq + mq)
// (AxisTransfer below; the GPU kernel uses these constants.) Summed over the volume, the L1 terms
// cancel between +e and -e and the L0 total is multiplied by 6 A / (c0 Y0) x c0 Y0 = 1 + 1.9e-5
// per step (the rounding of the published solid angles): energy is conserved until light leaves
// the volume. Clamping the flux instead would add the clipped negative lobe (+13.8% on the first
// step from a cosine VPL) and make the step non-linear.
#pragma once

#include <glm/vec3.hpp>

#include <array>

namespace lpv::gi {

inline constexpr float kFarFaceSolidAngle = 0.4006696846f;  // sr, seen from the neighbour centre
inline constexpr float kSideFaceSolidAngle = 0.4234413544f; // sr, each of the 4 side faces
// Direction from the neighbour centre to a side face's centre: (2/sqrt5) d + (1/sqrt5) s.
inline constexpr float kSideAxial = 0.894427191f;
inline constexpr float kSideLateral = 0.447213595f;

struct PropagationFace {
    glm::vec3 evalDirection; // neighbour centre -> face centre (unit)
    glm::vec3 normal;        // the face normal the flux is re-emitted along
    float solidAngle;
};

// The 6 axes d (neighbour -> destination), in order +x, -x, +y, -y, +z, -z.
inline const std::array<glm::ivec3, 6> kAxes{
    {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};

// The 5 faces of the destination seen from the neighbour on axis index `axis`.
std::array<PropagationFace, 5> propagationFaces(int axis);

// The non-zero entries of the per-axis transfer matrix (see above), in closed form.
struct AxisTransfer {
    float a, b, c, d, e;
};
AxisTransfer axisTransfer();

} // namespace lpv::gi
