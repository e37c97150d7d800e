#include "scene/gltf_loader.h"

#include <cmath>
#include <fstream>

#include "base/log.h"
#include "scene/gltf_import.h"

namespace prism {

namespace {

// Extensions whose meaning Prism implements. A file that requires any other is refused.
const std::set<std::string> kSupportedExtensions = {
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
    "KHR_materials_transmission",
    "KHR_materials_ior",
    "KHR_materials_volume",
    "KHR_materials_dispersion",
    "KHR_materials_specular",
    "KHR_materials_anisotropy",
    "KHR_texture_transform",
    "KHR_mesh_quantization",
};

// Images are kept encoded at load time and decoded only when a material that the scene's
// meshes use refers to them.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

bool is_binary_gltf(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in && std::string(magic, 4) == "glTF";
}

}  // namespace

double extension_number(const tinygltf::Material& m, const char* extension, const char* field, double fallback) {
  const auto it = m.extensions.find(extension);
  if (it == m.extensions.end() || !it->second.Has(field)) return fallback;
  const auto& v = it->second.Get(field);
  return v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
}

std::string prism_extra(const tinygltf::Material& m, const char* field) {
  if (!m.extras.IsObject() || !m.extras.Has("prism")) return {};
  const auto& prism = m.extras.Get("prism");
  if (!prism.IsObject() || !prism.Has(field) || !prism.Get(field).IsString()) return {};
  return prism.Get(field).Get<std::string>();
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

void GltfLoader::load() {
  check_extensions();
  traverse_scene();
  if (scene_.instances.empty()) log::warn("{}: the scene has no triangles", file_);
}

void GltfLoader::check_extensions() {
  for (const std::string& ext : model_.extensionsRequired)
    if (!kSupportedExtensions.count(ext)) fail("{}: requires extension {}, which Prism does not support", file_, ext);
  for (const std::string& ext : model_.extensionsUsed)
    if (!kSupportedExtensions.count(ext)) log::warn("{}: ignoring unsupported optional extension {}", file_, ext);
}

void GltfLoader::warn_once(const std::string& message) {
  if (warned_.insert(message).second) log::warn("{}: {}", file_, message);
}

Scene load_gltf(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) fail("{}: no such file", file.string());
  tinygltf::TinyGLTF reader;
  reader.SetImageLoader(keep_encoded_image, nullptr);
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
