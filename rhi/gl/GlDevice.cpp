// TEMPORARY: replaced by the real GL backend.
#include "../src/BackendFactory.h"
#include "rhi/Error.h"
namespace lpv::rhi {
std::unique_ptr<Device> createGlDevice(const DeviceConfig&) { throw BackendUnavailable("gl backend not built yet"); }
}
