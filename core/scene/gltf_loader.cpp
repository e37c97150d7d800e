#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <cmath>
#include <fstream>
#include <set>

#include "base/error.h"
#include "base/log.h"
#include "scene/gltf_accessor.h"

namespace prism {

namespace {

// Extensions whose meaning Prism implements. A file that requires any other is refused.
const std::set<std::string> kSupportedExtensions = {
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
};

// Images are not decoded at load time: Prism reads only what a scene's materials use.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

class GltfLoader {
 public:
  GltfLoader(const tinygltf::Model& model, const std::filesystem::path& file, Scene& scene)
      : model_(model), file_(file.string()), scene_(scene), meshes_(model.meshes.size()),
        mesh_loaded_(model.meshes.size(), false) {}

  void load() {
    check_extensions();
    traverse_scene();
    if (scene_.instances.empty()) log::warn("{}: the scene has no triangles", file_);
  }

 private:
  void check_extensions() {
    for (const std::string& ext : model_.extensionsRequired)
      if (!kSupportedExtensions.count(ext)) fail("{}: requires extension {}, which Prism does not support", file_, ext);
    for (const std::string& ext : model_.extensionsUsed)
      if (!kSupportedExtensions.count(ext)) log::warn("{}: ignoring unsupported optional extension {}", file_, ext);
  }

  template <typename Vec>
  void check_index(int index, const Vec& items, const char* what, const std::string& context) const {
    if (index < 0 || size_t(index) >= items.size())
      fail("{}: {} refers to {} {}, which does not exist ({} in file)", file_, context, what, index, items.size());
  }

  void warn_once(const std::string& message) {
    if (warned_.insert(message).second) log::warn("{}: {}", file_, message);
  }

  // --- materials ---------------------------------------------------------------------------

  Material convert_material(const tinygltf::Material& m, int index) {
    const std::string context = fmt::format("material {} '{}'", index, m.name);
    Material out;
    out.name = m.name.empty() ? fmt::format("material{}", index) : m.name;
    out.double_sided = m.doubleSided;
    const auto& bc = m.pbrMetallicRoughness.baseColorFactor;
    if (bc.size() != 4 || !all_finite(bc)) fail("{}: {}: baseColorFactor must be 4 finite numbers", file_, context);
    out.kind = DiffuseMaterial{RgbAlbedoSpectrum(Rgb{float(bc[0]), float(bc[1]), float(bc[2])})};
    if (m.pbrMetallicRoughness.baseColorTexture.index >= 0)
      warn_once("textures are not supported yet; using the material factors only");

    const auto& ef = m.emissiveFactor;
    if (ef.size() != 3 || !all_finite(ef)) fail("{}: {}: emissiveFactor must be 3 finite numbers", file_, context);
    double strength = 1;
    if (const auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
      const auto& v = it->second.Get("emissiveStrength");
      if (v.IsNumber()) strength = v.GetNumberAsDouble();
      if (!std::isfinite(strength) || strength < 0)
        fail("{}: {}: emissiveStrength must be a non-negative number", file_, context);
    }
    const Rgb emission{float(ef[0] * strength), float(ef[1] * strength), float(ef[2] * strength)};
    if (emission.max() > 0) out.emission = RgbIlluminantSpectrum(emission);
    return out;
  }

  uint32_t material_index(int gltf_material, const std::string& context) {
    if (gltf_material < 0) {
      // glTF's default material is white; Prism renders it as a white diffuse surface.
      if (default_material_ < 0) {
        default_material_ = int(scene_.materials.size());
        scene_.materials.push_back({"default", DiffuseMaterial{RgbAlbedoSpectrum(Rgb{1, 1, 1})}, {}, false});
      }
      return uint32_t(default_material_);
    }
    check_index(gltf_material, model_.materials, "material", context);
    auto [it, inserted] = material_map_.try_emplace(gltf_material, uint32_t(scene_.materials.size()));
    if (inserted) scene_.materials.push_back(convert_material(model_.materials[gltf_material], gltf_material));
    return it->second;
  }

  // --- meshes ------------------------------------------------------------------------------

  // Scene meshes (one per triangle primitive) of glTF mesh `index`, converted on first use.
  const std::vector<uint32_t>& mesh(int index) {
    if (mesh_loaded_[index]) return meshes_[index];
    mesh_loaded_[index] = true;
    const tinygltf::Mesh& m = model_.meshes[index];
    for (size_t p = 0; p < m.primitives.size(); ++p) {
      const std::string context = fmt::format("{}: mesh {} '{}' primitive {}", file_, index, m.name, p);
      if (auto converted = convert_primitive(m.primitives[p], context)) {
        converted->name = m.name.empty() ? fmt::format("mesh{}", index) : m.name;
        meshes_[index].push_back(uint32_t(scene_.meshes.size()));
        scene_.meshes.push_back(std::move(*converted));
      }
    }
    return meshes_[index];
  }

  std::optional<Mesh> convert_primitive(const tinygltf::Primitive& prim, const std::string& context) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
      warn_once(fmt::format("skipping primitives of mode {} (only triangles are rendered)", prim.mode));
      return std::nullopt;
    }
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) {
      warn_once("skipping primitives without POSITION data");
      return std::nullopt;
    }
    if (pos->second >= 0 && size_t(pos->second) < model_.accessors.size()) {
      // Compressed meshes (Draco, meshopt) keep their positions elsewhere and their accessors
      // hold no data. Reading them as zeros would give never-hit triangles that still take
      // triangle ids, unlike raybench, whose global numbering `prism bench rays` follows.
      const tinygltf::Accessor& acc = model_.accessors[pos->second];
      if (acc.bufferView < 0 && !acc.sparse.isSparse) {
        warn_once("skipping primitives whose POSITION accessor has no data (compressed meshes are not supported)");
        return std::nullopt;
      }
    }
    Mesh mesh;
    const auto p = read_accessor_floats(model_, pos->second, 3, context + " POSITION");
    mesh.positions.resize(p.size() / 3);
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      mesh.positions[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
      if (!is_finite(mesh.positions[i])) fail("{} POSITION: vertex {} is not finite", context, i);
    }
    if (const auto nrm = prim.attributes.find("NORMAL"); nrm != prim.attributes.end()) {
      const auto n = read_accessor_floats(model_, nrm->second, 3, context + " NORMAL");
      if (n.size() != p.size()) fail("{} NORMAL: {} normals for {} vertices", context, n.size() / 3, p.size() / 3);
      mesh.normals.resize(mesh.positions.size());
      for (size_t i = 0; i < mesh.normals.size(); ++i) {
        const Vec3f v(n[3 * i], n[3 * i + 1], n[3 * i + 2]);
        const float len = length(v);
        mesh.normals[i] = len > 0 && std::isfinite(len) ? v / len : Vec3f(0, 0, 0);  // 0: use the face normal
      }
    }
    if (prim.indices >= 0) {
      mesh.indices = read_accessor_indices(model_, prim.indices, context + " indices");
      for (uint32_t i : mesh.indices)
        if (i >= mesh.positions.size())
          fail("{} indices: index {} out of range ({} vertices)", context, i, mesh.positions.size());
    } else {
      mesh.indices.resize(mesh.positions.size());
      for (uint32_t i = 0; i < mesh.indices.size(); ++i) mesh.indices[i] = i;
    }
    if (mesh.indices.size() % 3 != 0) {
      warn_once("dropping a trailing partial triangle");
      mesh.indices.resize(mesh.indices.size() - mesh.indices.size() % 3);
    }
    mesh.material = material_index(prim.material, context);
    return mesh;
  }

  // --- nodes -------------------------------------------------------------------------------

  Transform local_transform(const tinygltf::Node& node, const std::string& context) const {
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16 || !all_finite(node.matrix)) fail("{}: matrix must be 16 finite numbers", context);
      return Transform::from_column_major(node.matrix.data());
    }
    Transform t;
    if (!node.translation.empty()) {
      if (node.translation.size() != 3 || !all_finite(node.translation))
        fail("{}: translation must be 3 finite numbers", context);
      t = Transform::translate({node.translation[0], node.translation[1], node.translation[2]});
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4 || !all_finite(node.rotation)) fail("{}: rotation must be 4 finite numbers", context);
      t = t * Transform::rotate(node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]);
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3 || !all_finite(node.scale)) fail("{}: scale must be 3 finite numbers", context);
      t = t * Transform::scale({node.scale[0], node.scale[1], node.scale[2]});
    }
    return t;
  }

  void traverse_scene() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      const int s = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      check_index(s, model_.scenes, "scene", "the default scene");
      roots = model_.scenes[s].nodes;
    } else {
      std::vector<bool> is_child(model_.nodes.size(), false);
      for (const auto& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && size_t(c) < is_child.size()) is_child[c] = true;
      for (size_t i = 0; i < model_.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(int(i));
    }
    std::vector<bool> on_path(model_.nodes.size(), false);
    for (int root : roots) {
      check_index(root, model_.nodes, "node", "the scene");
      visit(root, Transform{}, on_path);
    }
  }

  void visit(int index, const Transform& parent, std::vector<bool>& on_path) {
    if (on_path[index]) fail("{}: node {} is its own ancestor (cycle in the node hierarchy)", file_, index);
    on_path[index] = true;
    const tinygltf::Node& node = model_.nodes[index];
    const std::string context = fmt::format("{}: node {} '{}'", file_, index, node.name);
    const Transform world = parent * local_transform(node, context);
    if (node.mesh >= 0) {
      check_index(node.mesh, model_.meshes, "mesh", context);
      for (uint32_t m : mesh(node.mesh)) scene_.instances.push_back({m, world});
    }
    if (node.camera >= 0) {
      check_index(node.camera, model_.cameras, "camera", context);
      add_camera(model_.cameras[node.camera], world, context);
    }
    if (const auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
      const auto& light = it->second.Get("light");
      if (!light.IsInt()) fail("{}: KHR_lights_punctual without a light index", context);
      check_index(light.GetNumberAsInt(), model_.lights, "light", context);
      add_light(model_.lights[light.GetNumberAsInt()], world, context);
    }
    for (int child : node.children) {
      check_index(child, model_.nodes, "child node", context);
      visit(child, world, on_path);
    }
    on_path[index] = false;
  }

  void add_camera(const tinygltf::Camera& cam, const Transform& world, const std::string& context) {
    CameraDesc c;
    c.name = cam.name;
    c.to_world = world;
    if (cam.type == "perspective") {
      c.yfov = float(cam.perspective.yfov);
      if (!(c.yfov > 0 && c.yfov < kPi)) fail("{}: camera '{}' has yfov {} (needs 0 < yfov < π)", context, cam.name, c.yfov);
      if (cam.perspective.aspectRatio > 0) c.aspect = float(cam.perspective.aspectRatio);
    } else if (cam.type == "orthographic") {
      c.projection = CameraDesc::Projection::orthographic;
      c.xmag = float(std::abs(cam.orthographic.xmag));
      c.ymag = float(std::abs(cam.orthographic.ymag));
      if (!(c.xmag > 0 && c.ymag > 0)) fail("{}: orthographic camera '{}' needs non-zero xmag and ymag", context, cam.name);
      c.aspect = c.xmag / c.ymag;
    } else {
      fail("{}: camera '{}' has unknown type '{}'", context, cam.name, cam.type);
    }
    scene_.cameras.push_back(c);
  }

  void add_light(const tinygltf::Light& light, const Transform& world, const std::string& context) {
    if (light.type != "point") {
      warn_once(fmt::format("{} lights are not supported yet; ignoring them", light.type));
      return;
    }
    Rgb color{1, 1, 1};
    if (!light.color.empty()) {
      if (light.color.size() != 3 || !all_finite(light.color)) fail("{}: light color must be 3 finite numbers", context);
      color = {float(light.color[0]), float(light.color[1]), float(light.color[2])};
    }
    if (!std::isfinite(light.intensity) || light.intensity < 0)
      fail("{}: light '{}' has invalid intensity {}", context, light.name, light.intensity);
    // glTF point light intensity is in candela (KHR_lights_punctual); see PointLight for units.
    const Vec3f position(world.point({0, 0, 0}));
    scene_.point_lights.push_back({light.name, position, RgbIlluminantSpectrum(color * float(light.intensity))});
  }

  const tinygltf::Model& model_;
  std::string file_;
  Scene& scene_;
  std::vector<std::vector<uint32_t>> meshes_;
  std::vector<bool> mesh_loaded_;
  std::map<int, uint32_t> material_map_;
  int default_material_ = -1;
  std::set<std::string> warned_;
};

bool is_binary_gltf(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in && std::string(magic, 4) == "glTF";
}

}  // namespace

Scene load_gltf(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) fail("{}: no such file", file.string());
  tinygltf::TinyGLTF reader;
  reader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const bool ok = is_binary_gltf(file) ? reader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                                       : reader.LoadASCIIFromFile(&model, &err, &warn, file.string());
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    fail("{}: not a valid glTF file: {}", file.string(), err.empty() ? "unknown error" : err);
  }
  Scene scene;
  scene.source = file;
  GltfLoader(model, file, scene).load();
  return scene;
}

}  // namespace prism
