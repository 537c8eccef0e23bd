// Face geometry of the propagation scheme.
#include "gi/PropagationScheme.h"

#include "gi/ShBasis.h"

namespace lpv::gi {

std::array<PropagationFace, 5> propagationFaces(int axis) {
    const glm::vec3 d(kAxes[size_t(axis)]);
    // The two axes perpendicular to d, each with both signs, give the 4 side faces.
    const int a = axis / 2;
    const glm::vec3 u = a == 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 v = a == 2 ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    std::array<PropagationFace, 5> faces{};
    faces[0] = {d, d, kFarFaceSolidAngle};
    const glm::vec3 sides[4] = {u, -u, v, -v};
    for (int i = 0; i < 4; ++i)
        faces[size_t(i) + 1] = {kSideAxial * d + kSideLateral * sides[i], sides[i], kSideFaceSolidAngle};
    return faces;
}

AxisTransfer axisTransfer() {
    // Far face: W_F lobe(e) basis(e)^T. Side faces in +-q: their lobes' L0 terms add, their q
    // terms differ in sign twice and add too; the lateral parts of the evaluation cancel.
    const float wf = kFarFaceSolidAngle / kPi, ws = kSideFaceSolidAngle / kPi;
    return {kCosLobeC0 * kShY0 * (wf + 4.0f * ws), kCosLobeC0 * kShY1 * (wf + 4.0f * kSideAxial * ws),
            kCosLobeC1 * kShY0 * wf, kCosLobeC1 * kShY1 * wf, 2.0f * kCosLobeC1 * kShY1 * kSideLateral * ws};
}

} // namespace lpv::gi
