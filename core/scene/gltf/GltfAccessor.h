// Reads glTF accessors from a loaded tinygltf model: any component type the spec allows
// (normalized integers mapped as glTF 2.0 §3.11 says), interleaved data (byteStride), accessors
// without a buffer view (all zeros) and sparse accessors. Bounds were checked on the JSON
// (GltfValidateData.cpp); the reader checks them again against the loaded bytes, because a read
// outside a buffer must be impossible whatever went before. Data errors (sparse indices out of
// order or range) are InputErrors naming the accessor.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/gltf/TinyGltf.h"

namespace fovea::scene::gltf {

// `components` floats per element, element after element. The accessor must have exactly that
// many components (SCALAR = 1, VEC2 = 2, VEC3 = 3).
std::vector<float> readAccessorFloats(const tinygltf::Model& model, size_t accessor,
                                      uint32_t components, const std::string& file);

// A SCALAR accessor of unsigned integers (indices).
std::vector<uint32_t> readAccessorIndices(const tinygltf::Model& model, size_t accessor,
                                          const std::string& file);

}  // namespace fovea::scene::gltf
