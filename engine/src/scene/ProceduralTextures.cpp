// TEMPORARY placeholder, replaced by the atrium builder's texture generators.
#include "ProceduralTextures.h"
