// A surface face's area word (gi/SurfaceVoxels.h's areas()): the pass's stamp above the low
// kAreaCountBits, the samples counted in them. SurfaceVoxels::kAreaCountBits is the same width;
// the test that reads the counts back decodes them with it.
#ifndef SURFACE_AREAS_GLSL
#define SURFACE_AREAS_GLSL
const uint kAreaCountBits = 12u;
const uint kAreaCountMask = (1u << kAreaCountBits) - 1u;
#endif
