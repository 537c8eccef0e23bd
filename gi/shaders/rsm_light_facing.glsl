// Where two faces lie back to back in one plane (a trim or slab laid flat on a wall, a slab's top
// flush with a ceiling), the RSM would keep whichever the rasterizer's last bits of depth favour:
// a different one per backend (GL's and Vulkan's shader compilers round the transform apart), so
// the VPLs there took the wall's albedo on one and the slab's on the other. The face turned toward
// the light is the one it lights, so the other side loses the tie: its depth moves back by a few
// ulps of D32F plus a sixty-fourth of its slope per texel (the rasterizer snaps vertices to 1/256
// texel), far below anything the RSM's positions resolve (0.07 mm in a 32^3 volume of 0.25 m
// cells). depth_greater keeps the early depth test on hardware that has one.
layout(depth_greater) out float gl_FragDepth;

void writeLightFacingDepth(bool facesLight) {
    float z = gl_FragCoord.z;
    float slope = fwidth(z); // outside the select: derivatives need every lane
    gl_FragDepth = facesLight ? z : z + 1.9e-6 + slope * (1.0 / 64.0);
}
