// Scripted cameras for repeatable runs and benchmarks (--camera-path), defined relative to the
// scene's bounds so they work on any scene.
#pragma once

#include "engine/scene/Scene.h"

#include <string>
#include <string_view>
#include <vector>

namespace lpv::engine {

std::vector<std::string> cameraPathNames(); // "orbit", "flythrough"
bool isCameraPath(std::string_view name);
// The camera at time t in [0, 1] along the path. `start` is the scene's own camera (or a default),
// whose lens settings are kept; the orbit turns it once around the scene (t = 0 and 1: `start`),
// the flythrough crosses the scene at eye height. Throws std::invalid_argument for an unknown
// path name.
Camera cameraOnPath(std::string_view name, const Bounds& bounds, const Camera& start, float t);

} // namespace lpv::engine
