// EXT_mesh_gpu_instancing: a node draws its mesh once per instance, each placed by the node's
// world transform times the instance's own translation, rotation and scale (accessors
// TRANSLATION, ROTATION, SCALE; any of them may be absent). Spec:
// github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Vendor/EXT_mesh_gpu_instancing

#include <cmath>

#include "core/scene/gltf_accessor.h"
#include "core/scene/gltf_import.h"

namespace prism {

uint64_t GltfLoader::gpu_instance_count(const tinygltf::Node& node) const {
  const auto it = node.extensions.find("EXT_mesh_gpu_instancing");
  if (it == node.extensions.end() || !it->second.Get("attributes").IsObject()) return 1;
  const tinygltf::Value& attributes = it->second.Get("attributes");
  for (const char* name : {"TRANSLATION", "ROTATION", "SCALE"})
    if (const auto& index = attributes.Get(name);
        index.IsInt() && index.GetNumberAsInt() >= 0 && size_t(index.GetNumberAsInt()) < model_.accessors.size())
      return model_.accessors[index.GetNumberAsInt()].count;
  return 1;  // add_gpu_instances names what is wrong
}

void GltfLoader::add_gpu_instances(const tinygltf::Node& node, const std::vector<uint32_t>& meshes,
                                   const Transform& world, const std::string& context) {
  const tinygltf::Value& ext = node.extensions.at("EXT_mesh_gpu_instancing");
  if (!ext.Has("attributes") || !ext.Get("attributes").IsObject())
    fail("{}: EXT_mesh_gpu_instancing needs attributes", context);
  const auto& attributes = ext.Get("attributes");
  size_t count = 0;
  bool counted = false;
  // The attribute's values, `components` per instance, all instances counted alike.
  const auto read = [&](const char* name, int components) -> std::vector<float> {
    if (!attributes.Has(name)) return {};
    const auto& index = attributes.Get(name);
    if (!index.IsInt()) fail("{}: EXT_mesh_gpu_instancing {} must be an accessor index", context, name);
    const std::string what = fmt::format("{} EXT_mesh_gpu_instancing {}", context, name);
    std::vector<float> values = read_accessor_floats(model_, index.GetNumberAsInt(), components, what);
    for (size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i])) fail("{}: instance {} is not finite", what, i / components);
    if (counted && values.size() / components != count)
      fail("{}: {} instances, the other attributes have {}", what, values.size() / components, count);
    count = values.size() / components, counted = true;
    return values;
  };
  const auto translation = read("TRANSLATION", 3), rotation = read("ROTATION", 4), scale = read("SCALE", 3);
  if (!counted) fail("{}: EXT_mesh_gpu_instancing has none of TRANSLATION, ROTATION, SCALE", context);
  scene_.instances.reserve(scene_.instances.size() + count * meshes.size());
  for (size_t i = 0; i < count; ++i) {
    // T · R · S, as a node's own transform (glTF 2.0 §3.5.3).
    Transform local = rotation.empty() ? Transform{}
                                       : Transform::rotate(rotation[4 * i], rotation[4 * i + 1], rotation[4 * i + 2],
                                                           rotation[4 * i + 3]);
    for (int c = 0; c < 3; ++c) {
      if (!scale.empty())
        for (int r = 0; r < 3; ++r) local.m[r][c] *= scale[3 * i + c];
      if (!translation.empty()) local.m[c][3] = translation[3 * i + c];
    }
    const Transform to_world = world * local;
    for (uint32_t m : meshes) {
      check_world_bounds(m, to_world, context);
      scene_.instances.push_back({m, to_world});
    }
  }
}

}  // namespace prism
