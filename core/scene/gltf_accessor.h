#pragma once
// Bounds-checked reading of glTF accessors (positions, normals, indices), including strided
// views, normalized integer components and sparse substitution.

#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace prism {

// Elements of accessor `index` as `components` floats each (float, or integer components,
// normalized if the accessor says so). `what` names the data in error messages.
std::vector<float> read_accessor_floats(const tinygltf::Model& model, int index, int components,
                                        const std::string& what);

// Components per element of accessor `index` (1 for SCALAR, 3 for VEC3, ...).
int accessor_components(const tinygltf::Model& model, int index, const std::string& what);

// Elements of an unsigned-integer scalar accessor (u8, u16 or u32).
std::vector<uint32_t> read_accessor_indices(const tinygltf::Model& model, int index, const std::string& what);

}  // namespace prism
