#pragma once
// The glTF importer's inside, shared by its files (not a public header):
//   gltf_loader.cpp     reading the file, the extensions Prism honours, the import's order
//   gltf_materials.cpp  materials, textures and images
//   gltf_material_models.cpp  KHR_materials_unlit, KHR_materials_pbrSpecularGlossiness
//   gltf_meshes.cpp     primitives to triangle meshes; each node's copy of a mesh that deforms
//   gltf_nodes.cpp      the node hierarchy: instances, cameras, punctual lights
//   gltf_instancing.cpp EXT_mesh_gpu_instancing
//   gltf_animation.cpp  node poses and animation channels
//   gltf_morph.cpp, gltf_skin.cpp, gltf_variants.cpp  morph targets, skins, material variants

#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/scene/gltf_animation.h"
#include "core/scene/gltf_file.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/gltf_morph.h"
#include "core/scene/gltf_skin.h"
#include "core/scene/refractive_index_file.h"
#include "core/scene/scene.h"

namespace prism {

// A number from a material extension's object, or the extension's default (NaN if not a number).
double extension_number(const tinygltf::Material& m, const char* extension, const char* field, double fallback);

bool all_finite(const std::vector<double>& v);

// What Prism does with each glTF extension it implements, for `prism info`; null: unsupported.
const char* extension_handling(const std::string& extension);

// Converts one parsed glTF model into a Scene, checking every index it follows, and re-poses it
// at other times of its animations.
class GltfLoader {
 public:
  // Fails on `parse_errors` (the parser's, in a model it did build) after the extension check.
  // `json`: the file's JSON text when it holds Prism's extras (read_gltf_file), else empty.
  GltfLoader(const tinygltf::Model& model, const std::filesystem::path& file, const GltfOptions& options, Scene& scene,
             const std::string& parse_errors, SceneFiles& files, const std::string& json);

  void load();             // the scene as `options` choose it
  bool pose(double time);  // false: nothing moved
  bool animated() const;
  int scene_index() const { return scene_index_; }
  const std::vector<Animation>& animations() const { return animations_; }

 private:
  void check_extensions();
  void choose(const GltfOptions& options);
  std::vector<NodePose> pose_at(std::optional<double> time) const;
  void build();

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
  // extras {"prism": {…}} (gltf_extras.cpp): a material's catalogue materials and spectra, a
  // light's emission spectrum (read once per light), a refractiveindex.info file an extra names
  void material_extras(const tinygltf::Material& m, int index, Material& out, const std::string& context);
  Spectrum light_emission(const tinygltf::Light& light, Rgb rgb, const std::string& context);
  // A camera's thin lens from its extras.prism (none: a pinhole).
  LensDesc camera_lens(const tinygltf::Camera& camera, const std::string& context);
  OpticalConstants optical_constants_file(const nlohmann::json& uri, const std::string& what);
  // A medium, {"sigma_a": …, "sigma_s": …, "g": …} (a material's or the scene's).
  Medium medium_extras(const nlohmann::json& v, const std::string& what);
  // The scene's own extras.prism (its medium).
  void scene_extras();
  uint32_t material_index(int gltf_material, const std::string& context);
  Rgb clamp_emission(const std::array<double, 3>& rgb, const std::string& context);

  // older material models (gltf_material_models.cpp)
  void make_unlit(Material& out);
  void apply_spec_gloss(const tinygltf::Material& m, PbrMaterial& p, const std::string& context);

  // meshes (gltf_meshes.cpp)
  const std::vector<uint32_t>& mesh(int index);
  std::optional<Mesh> convert_primitive(const tinygltf::Primitive& prim, const std::string& context);

  // A primitive whose vertices move: its base attributes, morph targets and skin weights,
  // read once.
  struct Deformable {
    Mesh base;
    std::vector<MorphTarget> targets;
    SkinWeights skin;
    bool generated_tangents = false;
  };
  const std::vector<Deformable>& deformable(int mesh_index);
  bool deforms(const tinygltf::Node& node) const;
  void add_deformed(int node_index, const Transform& world);

  // nodes (gltf_nodes.cpp)
  void compute_node_world();
  void traverse_scene();
  uint64_t count_instances(const std::vector<int>& roots) const;
  void check_world_bounds(uint32_t mesh, const Transform& world, const std::string& context);
  void add_camera(const tinygltf::Camera& cam, const Transform& world, const std::string& context);
  // EXT_mesh_gpu_instancing (gltf_instancing.cpp); the count is 1 for a node without it
  uint64_t gpu_instance_count(const tinygltf::Node& node) const;
  void add_gpu_instances(const tinygltf::Node& node, const std::vector<uint32_t>& meshes, const Transform& world,
                         const std::string& context);
  void add_light(const tinygltf::Light& light, const Transform& world, const std::string& context);

  const tinygltf::Model& model_;
  SceneFiles& files_;                      // the files the scene reads (its spectrum tables through it)
  nlohmann::json document_;                // the file's JSON, when it holds Prism's extras (else null)
  std::map<int, Spectrum> light_spectra_;  // extras' emission spectra of the lights, by index
  std::string file_;
  Scene& scene_;
  int scene_index_ = 0;
  int variant_ = -1;    // KHR_materials_variants index, -1: default materials
  int animation_ = -1;  // the animation a time plays, -1: all (or the file has none)
  std::optional<double> time_;
  std::vector<Animation> animations_;
  std::vector<NodePose> pose_;
  std::vector<Transform> node_world_;
  std::map<int, std::vector<Deformable>> deformables_;  // by glTF mesh
  struct Deformed {
    std::vector<uint32_t> meshes;  // into scene_.meshes, one per primitive
    std::vector<double> inputs;    // the weights and joint matrices they were posed with
  };
  std::map<int, Deformed> deformed_;  // by node
  std::vector<std::vector<uint32_t>> meshes_;
  std::vector<bool> mesh_loaded_;
  std::map<int, uint32_t> material_map_;
  std::map<int, std::shared_ptr<const Image>> images_;
  std::vector<std::optional<std::pair<Vec3d, Vec3d>>> mesh_bounds_;  // per scene mesh, filled on first use
  uint64_t max_instances_;
  int default_material_ = -1;
  std::set<std::string> warned_;
};

}  // namespace prism
