#pragma once
// KHR_materials_variants: named material sets. The file lists the variants' names; each
// primitive maps some of them to a material of its own, and keeps its `material` otherwise.

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace prism {

std::vector<std::string> material_variants(const tinygltf::Model& model);

// Index of the variant called `name`; fails listing the file's variants when there is none.
int find_variant(const tinygltf::Model& model, const std::string& name, const std::string& file);

// The material the primitive has in `variant` (-1: the file's default materials).
int variant_material(const tinygltf::Primitive& prim, int variant);

}  // namespace prism
