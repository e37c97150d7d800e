#include "core/scene/gltf_variants.h"

#include "core/base/error.h"

namespace prism {

namespace {
constexpr const char* kVariants = "KHR_materials_variants";
}

std::vector<std::string> material_variants(const tinygltf::Model& model) {
  std::vector<std::string> names;
  const auto it = model.extensions.find(kVariants);
  if (it == model.extensions.end() || !it->second.Has("variants")) return names;
  const tinygltf::Value& list = it->second.Get("variants");
  for (size_t i = 0; i < list.ArrayLen(); ++i) {
    const tinygltf::Value& v = list.Get(int(i));
    names.push_back(v.Has("name") && v.Get("name").IsString() ? v.Get("name").Get<std::string>()
                                                              : "variant" + std::to_string(i));
  }
  return names;
}

int find_variant(const tinygltf::Model& model, const std::string& name, const std::string& file) {
  const std::vector<std::string> names = material_variants(model);
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return int(i);
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "'" : ", '") + n + "'";
  if (names.empty()) fail("{}: no material variant '{}' (the file has no KHR_materials_variants)", file, name);
  fail("{}: no material variant '{}' (the file has {})", file, name, list);
}

int variant_material(const tinygltf::Primitive& prim, int variant) {
  const auto it = prim.extensions.find(kVariants);
  if (variant < 0 || it == prim.extensions.end() || !it->second.Has("mappings")) return prim.material;
  const tinygltf::Value& mappings = it->second.Get("mappings");
  for (size_t m = 0; m < mappings.ArrayLen(); ++m) {
    const tinygltf::Value& mapping = mappings.Get(int(m));
    if (!mapping.Has("material") || !mapping.Get("material").IsInt() || !mapping.Has("variants")) continue;
    const tinygltf::Value& variants = mapping.Get("variants");
    for (size_t v = 0; v < variants.ArrayLen(); ++v)
      if (variants.Get(int(v)).IsInt() && variants.Get(int(v)).GetNumberAsInt() == variant)
        return mapping.Get("material").GetNumberAsInt();
  }
  return prim.material;
}

}  // namespace prism
