#version 450
#extension GL_GOOGLE_include_directive : require
// Propagation into RGBA8 volumes (32 bpp per SH texture, as on the consoles), range-encoded.
#define SH_FORMAT rgba8
#define SH_ENCODED 1
#include "propagate_body.glsl"
