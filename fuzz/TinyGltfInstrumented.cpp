// tinygltf's implementation, compiled into the fuzzers with their instrumentation. Debian ships it
// as a shared library (libtinygltf.so) built without sanitizers or coverage: the fuzzers would see
// nothing of the parser. The executable's definitions take precedence over the library's, for the
// engine's calls too.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
