#pragma once
// The glTF importer's inside, shared by its files (not a public header):
//   gltf_loader.cpp     reading the file, the extensions Prism honours, the import's order
//   gltf_materials.cpp  materials, textures and images
//   gltf_material_models.cpp  KHR_materials_unlit, KHR_materials_pbrSpecularGlossiness
//   gltf_meshes.cpp     primitives to triangle meshes
//   gltf_nodes.cpp      the node hierarchy: instances, cameras, punctual lights
//   gltf_instancing.cpp EXT_mesh_gpu_instancing

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "base/error.h"
#include "scene/scene.h"

namespace prism {

// A number from a material extension's object, or the extension's default (NaN if not a number).
double extension_number(const tinygltf::Material& m, const char* extension, const char* field, double fallback);

// A string under the material's extras: {"prism": {"metal": "Cu"}} names a catalogue material.
std::string prism_extra(const tinygltf::Material& m, const char* field);

bool all_finite(const std::vector<double>& v);

// Converts one parsed glTF model into a Scene, checking every index it follows.
class GltfLoader {
 public:
  GltfLoader(const tinygltf::Model& model, const std::filesystem::path& file, Scene& scene)
      : model_(model),
        file_(file.string()),
        scene_(scene),
        meshes_(model.meshes.size()),
        mesh_loaded_(model.meshes.size(), false) {}

  void load();

 private:
  void check_extensions();

  template <typename Vec>
  void check_index(int index, const Vec& items, const char* what, const std::string& context) const {
    if (index < 0 || size_t(index) >= items.size())
      fail("{}: {} refers to {} {}, which does not exist ({} in file)", file_, context, what, index, items.size());
  }

  void warn_once(const std::string& message);

  // materials (gltf_materials.cpp)
  Material convert_material(const tinygltf::Material& m, int index);
  std::shared_ptr<const Image> image(int index, const std::string& context);
  int texture_source(const tinygltf::Texture& t, int index, const std::string& context);  // gltf_texture_source.cpp
  std::optional<Texture> texture(int index, int texcoord, const tinygltf::ExtensionMap& extensions,
                                 const std::string& context);
  std::optional<Texture> extension_texture(const tinygltf::Material& m, const char* extension, const char* field,
                                           const std::string& context);
  PbrMaterial surface(const tinygltf::Material& m, Rgb base, const std::string& context);
  uint32_t material_index(int gltf_material, const std::string& context);

  // older material models (gltf_material_models.cpp)
  void make_unlit(Material& out);
  void apply_spec_gloss(const tinygltf::Material& m, PbrMaterial& p, const std::string& context);

  // meshes (gltf_meshes.cpp)
  const std::vector<uint32_t>& mesh(int index);
  std::optional<Mesh> convert_primitive(const tinygltf::Primitive& prim, const std::string& context);

  // nodes (gltf_nodes.cpp)
  Transform local_transform(const tinygltf::Node& node, const std::string& context) const;
  void traverse_scene();
  void visit(int index, const Transform& parent, std::vector<bool>& on_path);
  void add_camera(const tinygltf::Camera& cam, const Transform& world, const std::string& context);
  // EXT_mesh_gpu_instancing (gltf_instancing.cpp)
  void add_gpu_instances(const tinygltf::Node& node, const std::vector<uint32_t>& meshes, const Transform& world,
                         const std::string& context);
  void add_light(const tinygltf::Light& light, const Transform& world, const std::string& context);

  const tinygltf::Model& model_;
  std::string file_;
  Scene& scene_;
  std::vector<std::vector<uint32_t>> meshes_;
  std::vector<bool> mesh_loaded_;
  std::map<int, uint32_t> material_map_;
  std::map<int, std::shared_ptr<const Image>> images_;
  int default_material_ = -1;
  std::set<std::string> warned_;
};

}  // namespace prism
