// How many of the finest cascades gi.gather gathers: gi/VplGather.h's kCascades, which sizes the
// gather's uniforms and the lookup's first-bounce bindings on the C++ side.
#ifndef GATHERED_CASCADES_GLSL
#define GATHERED_CASCADES_GLSL
#define GATHERED_CASCADES 3
#endif
