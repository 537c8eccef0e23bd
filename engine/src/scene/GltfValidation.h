// Checks on a parsed glTF model for what tinygltf leaves to its caller: every index that the reader
// follows names an element that exists, every accessor lies inside its buffer, and the nodes form
// disjoint trees; and no value is one the glTF 2.0 spec forbids (a version other than 2.x, a zero
// field of view, a negative light intensity). The reader can then follow the file's indices without
// checking each one again, and a broken file is an error naming the file and the element, not a
// crash, an out-of-range read or a NaN in the frame.
#pragma once

#include <tiny_gltf.h>

#include <string>

namespace lpv::engine {

// Throws SceneError(path, problem) for the first problem found.
void validateGltf(const std::string& path, const tinygltf::Model& model);

// What is wrong with a bufferView's byte range, "" when it lies inside its buffer; the view's buffer
// index must be valid. Checked without overflow, however large the numbers in the file.
std::string bufferViewRangeProblem(const tinygltf::Model& model, size_t view);

} // namespace lpv::engine
