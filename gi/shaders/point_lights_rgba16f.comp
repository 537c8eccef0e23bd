#version 450
#extension GL_GOOGLE_include_directive : require
// Analytic lights into RGBA16F volumes.
#define SH_FORMAT rgba16f
#include "point_lights_body.glsl"
