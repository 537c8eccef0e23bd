#version 450
#extension GL_GOOGLE_include_directive : require
// Analytic lights into RGBA32F volumes.
#define SH_FORMAT rgba32f
#include "point_lights_body.glsl"
