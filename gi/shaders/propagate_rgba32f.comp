#version 450
#extension GL_GOOGLE_include_directive : require
// Propagation into RGBA32F volumes.
#define SH_FORMAT rgba32f
#include "propagate_body.glsl"
