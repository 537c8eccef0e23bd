#version 450
#extension GL_GOOGLE_include_directive : require
// Propagation into RGBA16F volumes.
#define SH_FORMAT rgba16f
#include "propagate_body.glsl"
