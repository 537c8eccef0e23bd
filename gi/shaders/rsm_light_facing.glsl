// Where two faces lie back to back in one plane (a trim or slab laid flat on a wall, a slab's top
// flush with a ceiling), the RSM would keep whichever face the last bits of depth favour, and GL
// and Vulkan place depth a bit or two apart, so the VPLs there took the wall's albedo on one and
// the slab's on the other. The face turned toward the light is the one it lights, so the other
// side loses the tie: its depth moves back by 1.9e-6 (about 32 ulps of D32F in [0.5, 1), where the
// sun's RSM puts the volume: well past the ulp or two the backends differ by) plus a sixty-fourth
// of its slope per texel (the rasterizer snaps vertices to 1/256 texel). That moves a point by
// 0.07 mm in the sun's RSM of a 32^3 volume of 0.25 m cells, and by about 1e-3 of the far plane
// near it in a spot's (near = far / 500): 1 cm at 10 m, still far below a cell. depth_greater
// keeps the early depth test on hardware that honours it.
layout(depth_greater) out float gl_FragDepth;

void writeLightFacingDepth(bool facesLight) {
    float z = gl_FragCoord.z;
    float slope = fwidth(z); // outside the select: derivatives need every lane
    gl_FragDepth = facesLight ? z : z + 1.9e-6 + slope * (1.0 / 64.0);
}
