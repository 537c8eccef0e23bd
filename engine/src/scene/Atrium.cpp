// TEMPORARY placeholder, replaced by the atrium builder.
#include "engine/scene/BuiltinScenes.h"
namespace lpv::engine {
Scene buildAtrium(float) { return Scene{}; }
}
