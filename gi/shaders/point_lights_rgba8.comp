#version 450
#extension GL_GOOGLE_include_directive : require
// Analytic lights into RGBA8 volumes (range-encoded, as the propagation stores them).
#define SH_FORMAT rgba8
#define SH_ENCODED 1
#include "point_lights_body.glsl"
