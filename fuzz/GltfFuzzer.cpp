// libFuzzer harness for the glTF loader (loadGltf), built twice: as JSON (.gltf) and as binary
// (.glb; LPV_FUZZ_GLB). The loader reads files, so each input is written to a file of this
// process first. Bad input must end in a SceneError naming the file; any other exception, a crash
// or a sanitizer report is a finding.
#include "engine/scene/SceneLoading.h"
#include "platforms/Log.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

namespace {

#ifdef LPV_FUZZ_GLB
constexpr const char* kExtension = ".glb";
#else
constexpr const char* kExtension = ".gltf";
#endif

std::string inputPath() {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir && *dir ? dir : "/tmp") + "/lpv-fuzz-" + std::to_string(getpid()) + kExtension;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    lpv::log::setSink([](lpv::log::Level, std::string_view) {}); // warnings would flood the run
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = inputPath();
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) {
        std::perror(path.c_str());
        std::abort();
    }
    const bool written = std::fwrite(data, 1, size, file) == size;
    if (std::fclose(file) != 0 || !written) {
        std::perror(path.c_str());
        std::abort();
    }
    try {
        const lpv::engine::Scene scene = lpv::engine::loadGltf(path);
        (void)scene;
    } catch (const lpv::engine::SceneError&) {
        // The expected refusal: a message naming the file and the problem.
    } catch (const std::exception& e) {
        std::fprintf(stderr, "not a SceneError: %s\n", e.what());
        std::abort();
    }
    return 0;
}
