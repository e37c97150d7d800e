#include "core/scene/gltf_loader.h"

#include <cmath>

#include "core/base/log.h"
#include "core/scene/gltf_compression.h"
#include "core/scene/gltf_file.h"
#include "core/scene/gltf_import.h"
#include "core/scene/gltf_variants.h"

namespace prism {

namespace {

// Extensions whose meaning Prism implements, and what it does with each (`prism info` prints
// it). A file that requires any other is refused; an optional one is ignored with a warning.
const std::map<std::string, const char*> kSupportedExtensions = {
    {"KHR_materials_emissive_strength", "emission scaled by emissiveStrength"},
    {"KHR_lights_punctual", "point, spot and directional lights (range ignored)"},
    {"KHR_materials_transmission", "dielectric transmission, rough or smooth"},
    {"KHR_materials_ior", "the dielectric's index of refraction"},
    {"KHR_materials_volume", "closed volumes with Beer-Lambert absorption; thickness 0 is a thin wall"},
    {"KHR_materials_dispersion", "index varying with wavelength (Abbe number)"},
    {"KHR_materials_volume_scatter",
     "draft: the volume's attenuation scatters by multiscatterColor and scatterAnisotropy (factors, no textures)"},
    {"KHR_materials_specular", "specular strength and colour: the F0 of an exact Fresnel curve per wavelength"},
    {"KHR_materials_anisotropy", "anisotropic GGX along the tangent frame (strength, rotation, direction texture)"},
    {"KHR_texture_transform", "texture coordinate offset, rotation and scale"},
    {"KHR_mesh_quantization", "integer and normalized vertex attributes"},
    {"KHR_materials_variants", "material sets, chosen with --variant NAME"},
    {"KHR_materials_clearcoat", "a GGX dielectric coat (IOR 1.5) over the base, albedo-scaled layering"},
    {"KHR_materials_sheen", "Charlie sheen over the base, albedo-scaled layering"},
    {"KHR_materials_iridescence", "exact thin-film interference (Airy sum) per wavelength"},
    {"KHR_materials_diffuse_transmission", "a Lambertian lobe on the far side"},
    {"KHR_draco_mesh_compression", "Draco-compressed primitives decoded (libdraco)"},
    {"EXT_meshopt_compression", "meshoptimizer-compressed buffer views decoded"},
    {"KHR_meshopt_compression", "meshoptimizer-compressed buffer views decoded"},
    {"KHR_materials_unlit", "base colour emitted, nothing scattered"},
    {"KHR_materials_pbrSpecularGlossiness", "converted to metallic-roughness"},
    {"EXT_texture_webp", "WebP textures (libwebp)"},
    {"KHR_texture_basisu", "KTX2 not decoded: the texture's PNG/JPEG source is used"},
    {"EXT_mesh_gpu_instancing", "TRANSLATION, ROTATION, SCALE per instance, into the two-level BVH"},
};

// Images are kept encoded at load time and decoded only when a material that the scene's
// meshes use refers to them.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

}  // namespace

double extension_number(const tinygltf::Material& m, const char* extension, const char* field, double fallback) {
  const auto it = m.extensions.find(extension);
  if (it == m.extensions.end() || !it->second.Has(field)) return fallback;
  const auto& v = it->second.Get(field);
  return v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

const char* extension_handling(const std::string& extension) {
  const auto it = kSupportedExtensions.find(extension);
  return it == kSupportedExtensions.end() ? nullptr : it->second;
}

GltfLoader::GltfLoader(const tinygltf::Model& model, const std::filesystem::path& file, const GltfOptions& options,
                       Scene& scene, const std::string& parse_errors, SceneFiles& files, const std::string& json)
    : model_(model),
      files_(files),
      document_(json.empty() ? nlohmann::json() : nlohmann::json::parse(json, nullptr, false)),
      file_(file.string()),
      scene_(scene),
      meshes_(model.meshes.size()),
      mesh_loaded_(model.meshes.size(), false),
      max_instances_(options.max_instances) {
  check_extensions();
  if (!parse_errors.empty()) fail("{}: not a valid glTF file: {}", file_, parse_errors);
  choose(options);
}

void GltfLoader::load() {
  scene_extras();
  pose_ = pose_at(time_);
  build();
  if (scene_.instances.empty()) log::warn("{}: the scene has no triangles", file_);
}

void GltfLoader::choose(const GltfOptions& options) {
  if (model_.defaultScene < -1) fail("{}: scene index {} is negative", file_, model_.defaultScene);
  scene_index_ = options.scene.value_or(model_.defaultScene >= 0 ? model_.defaultScene : 0);
  if (options.scene && size_t(*options.scene) >= std::max<size_t>(model_.scenes.size(), 1))
    fail("{}: --scene {} requested, but the file has {} scene(s)", file_, *options.scene, model_.scenes.size());
  if (!options.variant.empty()) variant_ = find_variant(model_, options.variant, file_);
  animations_ = read_animations(model_, file_);
  const bool named = !options.animation.empty() && options.animation != "all";
  if (named)
    animation_ = find_animation(animations_, options.animation, file_);
  else if (options.animation.empty() && !animations_.empty())
    animation_ = 0;
  if (options.animation.empty() && animations_.size() > 1)
    log::info("{}: {} animations; a time plays the first, '{}' (--animation NAME, INDEX or all to choose)", file_,
              animations_.size(), animations_[0].name);
  if (animation_ < 0) warn_of_shared_targets(animations_, model_, file_);
  time_ = options.time;
  if (!time_ && named) time_ = animations_[size_t(animation_)].start;
  if (time_ && !std::isfinite(*time_)) fail("{}: the time must be a finite number of seconds", file_);
}

bool GltfLoader::animated() const {
  for (size_t a = 0; a < animations_.size(); ++a)
    if ((animation_ < 0 || int(a) == animation_) && !animations_[a].channels.empty()) return true;
  return false;
}

std::vector<NodePose> GltfLoader::pose_at(std::optional<double> time) const {
  std::vector<NodePose> pose = rest_pose(model_, file_);
  if (time)
    for (size_t a = 0; a < animations_.size(); ++a)
      if (animation_ < 0 || int(a) == animation_) animate(animations_[a], *time, pose);
  return pose;
}

bool GltfLoader::pose(double time) {
  std::vector<NodePose> pose = pose_at(time);
  if (pose == pose_) return false;
  pose_ = std::move(pose);
  build();
  return true;
}

// The instances, cameras, lights and deformed meshes of the current pose.
void GltfLoader::build() {
  scene_.instances.clear();
  scene_.named_nodes.clear();
  scene_.node_origins.clear();
  scene_.cameras.clear();
  scene_.point_lights.clear();
  scene_.spot_lights.clear();
  scene_.directional_lights.clear();
  compute_node_world();
  traverse_scene();
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

// The parsed file, the scene built from it and the loader that keeps it posed; they refer to
// each other, so they stay together at one address.
struct GltfScene::State {
  std::unique_ptr<tinygltf::Model> model;
  Scene scene;
  SceneFiles files;
  std::unique_ptr<GltfLoader> loader;
  State(const std::filesystem::path& file, const GltfOptions& options)
      : model(std::make_unique<tinygltf::Model>()), files(file, options.allow_external_paths) {
    tinygltf::TinyGLTF reader;
    reader.SetImageLoader(keep_encoded_image, nullptr);
    std::string json;
    const std::string errors = read_gltf_file(reader, *model, file, files, json);
    if (errors.empty()) {  // else the loader names them (after any required extension Prism lacks)
      decode_meshopt(*model, file.string());
      decode_draco(*model, file.string());
    }
    scene.source = file;
    loader = std::make_unique<GltfLoader>(*model, file, options, scene, errors, files, json);
  }
  const GltfLoader& open() const {
    if (!loader) fail("{}: internal error: the file was closed", scene.source.string());
    return *loader;
  }
};

GltfScene::GltfScene(const std::filesystem::path& file, const GltfOptions& options)
    : state_(std::make_unique<State>(file, options)) {
  state_->loader->load();
  state_->scene.source_hash = state_->files.hash();  // with the files the extras named
}

GltfScene::~GltfScene() = default;

Scene& GltfScene::scene() { return state_->scene; }
bool GltfScene::animated() const { return state_->open().animated(); }
bool GltfScene::pose(double seconds) {
  state_->open();
  return state_->loader->pose(seconds);
}

void GltfScene::close() {
  state_->loader.reset();
  state_->model.reset();
}

GltfSummary GltfScene::summary() const {
  state_->open();
  const tinygltf::Model& model = *state_->model;
  GltfSummary s;
  for (const auto& scene : model.scenes) s.scenes.push_back(scene.name);
  s.scene = state_->loader->scene_index();
  for (const auto& camera : model.cameras) s.cameras.push_back(camera.name);
  s.variants = material_variants(model);
  for (const Animation& a : state_->loader->animations())
    s.animations.push_back({a.name, a.start, a.end, a.channels.size()});
  for (const std::string& ext : model.extensionsUsed) {
    const bool required = std::count(model.extensionsRequired.begin(), model.extensionsRequired.end(), ext) > 0;
    const char* handling = extension_handling(ext);
    s.extensions.push_back({ext, required, handling ? handling : ""});
  }
  s.skins = model.skins.size();
  for (const auto& mesh : model.meshes)
    s.morphed_meshes += !mesh.primitives.empty() && !mesh.primitives[0].targets.empty();
  return s;
}

Scene load_gltf(const std::filesystem::path& file, const GltfOptions& options) {
  GltfScene gltf(file, options);
  return std::move(gltf.scene());
}

}  // namespace prism
