// The 6-neighbour, 5-face propagation scheme of Kaplanyan & Dachsbacher (Cascaded LPV, I3D 2010),
// shared by the CPU reference and the GPU kernels (whose shader constants must match these).
//
// A destination cell gathers from each of its 6 neighbours. From the neighbour's centre, the
// destination cell shows 5 faces: the far face (normal along the neighbour-to-destination axis d)
// and 4 side faces. The flux through a face is the neighbour's intensity in the direction of the
// face's centre times the face's solid angle; it is re-emitted from the face as a clamped-cosine
// lobe along the face normal, i.e. a VPL of that flux (intensity = flux / pi * cos).
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

} // namespace lpv::gi
