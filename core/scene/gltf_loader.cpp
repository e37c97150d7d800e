#include "scene/gltf_loader.h"

#include <tiny_gltf.h>

#include <cmath>
#include <fstream>
#include <set>

#include "base/error.h"
#include "base/log.h"
#include "materials/catalogue.h"
#include "scene/gltf_accessor.h"

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
    "KHR_texture_transform",
    "KHR_mesh_quantization",
};

// A number from a material extension's object, or the extension's default.
double extension_number(const tinygltf::Material& m, const char* extension, const char* field, double fallback) {
  const auto it = m.extensions.find(extension);
  if (it == m.extensions.end() || !it->second.Has(field)) return fallback;
  const auto& v = it->second.Get(field);
  return v.IsNumber() ? v.GetNumberAsDouble() : std::nan("");
}

// A string under the material's extras: {"prism": {"metal": "Cu"}} names a catalogue material.
std::string prism_extra(const tinygltf::Material& m, const char* field) {
  if (!m.extras.IsObject() || !m.extras.Has("prism")) return {};
  const auto& prism = m.extras.Get("prism");
  if (!prism.IsObject() || !prism.Has(field) || !prism.Get(field).IsString()) return {};
  return prism.Get(field).Get<std::string>();
}

// Images are kept encoded at load time and decoded only when a material that the scene's
// meshes use refers to them.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + size);
  return true;
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

class GltfLoader {
 public:
  GltfLoader(const tinygltf::Model& model, const std::filesystem::path& file, Scene& scene)
      : model_(model),
        file_(file.string()),
        scene_(scene),
        meshes_(model.meshes.size()),
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
    PbrMaterial surface_model = surface(m, Rgb{float(bc[0]), float(bc[1]), float(bc[2])}, context);
    surface_model.alpha = std::clamp(float(bc[3]), 0.f, 1.f);
    const auto& pbr = m.pbrMetallicRoughness;
    surface_model.base_color_texture =
        texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions, context);
    surface_model.metallic_roughness_texture =
        texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                pbr.metallicRoughnessTexture.extensions, context);
    surface_model.transmission_texture =
        extension_texture(m, "KHR_materials_transmission", "transmissionTexture", context);
    surface_model.thickness_texture = extension_texture(m, "KHR_materials_volume", "thicknessTexture", context);
    out.kind = std::move(surface_model);
    out.normal_texture = texture(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions, context);
    out.normal_scale = float(m.normalTexture.scale);
    if (m.alphaMode == "MASK")
      out.alpha_mode = AlphaMode::mask;
    else if (m.alphaMode == "BLEND")
      out.alpha_mode = AlphaMode::blend;
    else if (m.alphaMode != "OPAQUE")
      fail("{}: {}: unknown alphaMode '{}'", file_, context, m.alphaMode);
    out.alpha_cutoff = float(m.alphaCutoff);
    const auto& ef = m.emissiveFactor;
    if (ef.size() != 3 || !all_finite(ef)) fail("{}: {}: emissiveFactor must be 3 finite numbers", file_, context);
    double strength = 1;
    if (const auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
      const auto& v = it->second.Get("emissiveStrength");
      if (v.IsNumber()) strength = v.GetNumberAsDouble();
      if (!std::isfinite(strength) || strength < 0)
        fail("{}: {}: emissiveStrength must be a non-negative number", file_, context);
    }
    out.emission_rgb = {float(ef[0] * strength), float(ef[1] * strength), float(ef[2] * strength)};
    if (out.emission_rgb.max() > 0) {
      out.emission = RgbIlluminantSpectrum(out.emission_rgb);
      out.emission_texture =
          texture(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions, context);
    }
    return out;
  }

  // --- textures -----------------------------------------------------------------------------

  // The decoded image of glTF image `index` (decoded once, on first use).
  std::shared_ptr<const Image> image(int index, const std::string& context) {
    check_index(index, model_.images, "image", context);
    auto& cached = images_[index];
    if (cached) return cached;
    const tinygltf::Image& img = model_.images[index];
    if (img.image.empty()) fail("{}: {}: image {} has no data", file_, context, index);
    cached = Image::decode(img.image.data(), img.image.size(),
                           fmt::format("{}: image {} '{}'", file_, index, img.uri.empty() ? img.name : img.uri));
    return cached;
  }

  // glTF texture `index` read with TEXCOORD_`texcoord` and its KHR_texture_transform, or nothing.
  std::optional<Texture> texture(int index, int texcoord, const tinygltf::ExtensionMap& extensions,
                                 const std::string& context) {
    if (index < 0) return std::nullopt;
    check_index(index, model_.textures, "texture", context);
    const tinygltf::Texture& t = model_.textures[index];
    if (t.source < 0) fail("{}: {}: texture {} has no image source", file_, context, index);
    Texture out;
    out.image = image(t.source, context);
    out.texcoord = texcoord;
    if (t.sampler >= 0) {
      check_index(t.sampler, model_.samplers, "sampler", context);
      const tinygltf::Sampler& s = model_.samplers[t.sampler];
      const auto wrap = [&](int mode) {
        if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return Wrap::clamp_to_edge;
        if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return Wrap::mirrored_repeat;
        return Wrap::repeat;
      };
      out.wrap_s = wrap(s.wrapS);
      out.wrap_t = wrap(s.wrapT);
      out.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    }
    if (const auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
      const auto& x = it->second;
      const auto vec2 = [&](const char* key, Vec2f fallback) {
        if (!x.Has(key)) return fallback;
        const auto& v = x.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2)
          fail("{}: {}: KHR_texture_transform.{} must hold 2 numbers", file_, context, key);
        return Vec2f(float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble()));
      };
      out.transform.offset = vec2("offset", {0, 0});
      out.transform.scale = vec2("scale", {1, 1});
      if (x.Has("rotation")) out.transform.rotation = float(x.Get("rotation").GetNumberAsDouble());
      if (x.Has("texCoord")) out.texcoord = x.Get("texCoord").GetNumberAsInt();
    }
    if (out.texcoord < 0 || out.texcoord > 1)
      fail("{}: {}: texture coordinate set {} (Prism reads TEXCOORD_0 and _1)", file_, context, out.texcoord);
    return out;
  }

  // A texture named inside a material extension, e.g. KHR_materials_transmission's transmissionTexture.
  std::optional<Texture> extension_texture(const tinygltf::Material& m, const char* extension, const char* field,
                                           const std::string& context) {
    const auto it = m.extensions.find(extension);
    if (it == m.extensions.end() || !it->second.Has(field)) return std::nullopt;
    const auto& info = it->second.Get(field);
    if (!info.IsObject() || !info.Has("index")) fail("{}: {}: {}.{} needs an index", file_, context, extension, field);
    tinygltf::ExtensionMap ext;
    if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform"))
      ext["KHR_texture_transform"] = info.Get("extensions").Get("KHR_texture_transform");
    return texture(info.Get("index").GetNumberAsInt(), info.Has("texCoord") ? info.Get("texCoord").GetNumberAsInt() : 0,
                   ext, context);
  }

  // glTF's metallic-roughness parameters with the KHR extensions Prism honours; extras may name
  // a catalogue metal ({"prism": {"metal": "Cu"}}) or glass ({"prism": {"glass": "N-BK7"}}).
  PbrMaterial surface(const tinygltf::Material& m, Rgb base, const std::string& context) {
    const auto number = [&](const char* ext, const char* field, double fallback, double lo, double hi) {
      const double v = extension_number(m, ext, field, fallback);
      if (!(v >= lo && v <= hi)) fail("{}: {}: {}.{} must be a number in [{}, {}]", file_, context, ext, field, lo, hi);
      return v;
    };
    PbrMaterial p;
    p.base_color = base;
    p.metallic = std::clamp(float(m.pbrMetallicRoughness.metallicFactor), 0.f, 1.f);
    p.roughness = std::clamp(float(m.pbrMetallicRoughness.roughnessFactor), 0.f, 1.f);
    p.transmission = float(number("KHR_materials_transmission", "transmissionFactor", 0, 0, 1));
    p.specular = float(number("KHR_materials_specular", "specularFactor", 1, 0, 1));
    if (const auto it = m.extensions.find("KHR_materials_specular");
        it != m.extensions.end() && it->second.Has("specularColorFactor"))
      warn_once("KHR_materials_specular's specularColorFactor is not supported; using the factor only");

    IorModel ior_model = ConstantIor{float(number("KHR_materials_ior", "ior", 1.5, 1, 1e3))};
    if (const std::string glass = prism_extra(m, "glass"); !glass.empty()) {
      ior_model = MaterialCatalogue::standard().dielectric(glass);
      p.metallic = 0;
      p.transmission = 1;
    } else if (const double dispersion = number("KHR_materials_dispersion", "dispersion", 0, 0, 1e6); dispersion > 0) {
      // KHR_materials_dispersion: dispersion = 20 / V_d.
      ior_model = AbbeIor{std::get<ConstantIor>(ior_model).n, float(20 / dispersion)};
    }
    // KHR_materials_volume: thickness 0 is a thin wall; otherwise a closed volume absorbing with
    // σ_a = −ln(attenuationColor) / attenuationDistance per channel (world units).
    const double thickness = number("KHR_materials_volume", "thicknessFactor", 0, 0, 1e30);
    const double distance = number("KHR_materials_volume", "attenuationDistance", kInfinity, 0, kInfinity);
    std::optional<Spectrum> absorption;
    if (thickness > 0 && std::isfinite(distance)) {
      Rgb sigma;
      const auto color = m.extensions.at("KHR_materials_volume").Get("attenuationColor");
      for (int c = 0; c < 3; ++c) {
        const double a = color.IsArray() && color.ArrayLen() == 3 ? color.Get(c).GetNumberAsDouble() : 1.0;
        if (!(a >= 0 && a <= 1)) fail("{}: {}: attenuationColor must hold 3 numbers in [0, 1]", file_, context);
        sigma[c] = float(-std::log(std::max(a, 1e-30)) / std::max(distance, 1e-30));
      }
      if (sigma.max() > 0) absorption = RgbUnboundedSpectrum(sigma);
    }
    p.dielectric = Dielectric(std::move(ior_model), std::move(absorption), thickness == 0);
    if (const std::string metal = prism_extra(m, "metal"); !metal.empty()) {
      p.metal = MaterialCatalogue::standard().metal(metal);
      p.metallic = 1;
    }
    return p;
  }

  uint32_t material_index(int gltf_material, const std::string& context) {
    if (gltf_material < 0) {
      // glTF's default material: white, metallic 1, roughness 1 (glTF 2.0 §3.9.2).
      if (default_material_ < 0) {
        default_material_ = int(scene_.materials.size());
        scene_.materials.push_back({.name = "default", .kind = PbrMaterial{}});
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
    for (int set = 0; set < 2; ++set)
      if (const auto uv = prim.attributes.find("TEXCOORD_" + std::to_string(set)); uv != prim.attributes.end()) {
        const auto t = read_accessor_floats(model_, uv->second, 2, fmt::format("{} TEXCOORD_{}", context, set));
        if (t.size() / 2 != mesh.positions.size())
          fail("{} TEXCOORD_{}: {} entries for {} vertices", context, set, t.size() / 2, mesh.positions.size());
        for (size_t i = 0; i < t.size(); i += 2) mesh.uv[set].push_back({t[i], t[i + 1]});
      }
    if (const auto col = prim.attributes.find("COLOR_0"); col != prim.attributes.end()) {
      const int components = accessor_components(model_, col->second, context + " COLOR_0");
      if (components != 3 && components != 4) fail("{} COLOR_0: must be VEC3 or VEC4", context);
      const auto c = read_accessor_floats(model_, col->second, components, context + " COLOR_0");
      if (c.size() / components != mesh.positions.size())
        fail("{} COLOR_0: {} colours for {} vertices", context, c.size() / components, mesh.positions.size());
      for (size_t i = 0; i < c.size(); i += components)
        mesh.colors.push_back({c[i], c[i + 1], c[i + 2], components == 4 ? c[i + 3] : 1.f});
    }
    if (const auto tan = prim.attributes.find("TANGENT"); tan != prim.attributes.end()) {
      const auto t = read_accessor_floats(model_, tan->second, 4, context + " TANGENT");
      if (t.size() / 4 != mesh.positions.size())
        fail("{} TANGENT: {} tangents for {} vertices", context, t.size() / 4, mesh.positions.size());
      for (size_t i = 0; i < t.size(); i += 4)
        mesh.tangents.push_back({t[i], t[i + 1], t[i + 2], t[i + 3] < 0 ? -1.f : 1.f});
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
    const Material& material = scene_.materials[mesh.material];
    if (material.normal_texture && mesh.tangents.empty()) generate_tangents(mesh, material.normal_texture->texcoord);
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
      if (node.rotation.size() != 4 || !all_finite(node.rotation))
        fail("{}: rotation must be 4 finite numbers", context);
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
      if (!(c.yfov > 0 && c.yfov < kPi))
        fail("{}: camera '{}' has yfov {} (needs 0 < yfov < π)", context, cam.name, c.yfov);
      if (cam.perspective.aspectRatio > 0) c.aspect = float(cam.perspective.aspectRatio);
    } else if (cam.type == "orthographic") {
      c.projection = CameraDesc::Projection::orthographic;
      c.xmag = float(std::abs(cam.orthographic.xmag));
      c.ymag = float(std::abs(cam.orthographic.ymag));
      if (!(c.xmag > 0 && c.ymag > 0))
        fail("{}: orthographic camera '{}' needs non-zero xmag and ymag", context, cam.name);
      c.aspect = c.xmag / c.ymag;
    } else {
      fail("{}: camera '{}' has unknown type '{}'", context, cam.name, cam.type);
    }
    scene_.cameras.push_back(c);
  }

  // KHR_lights_punctual: intensity in candela (point, spot) or lux (directional), times the
  // linear colour, upsampled as an illuminant like emission (see the README's units). A spot or
  // directional light shines down its node's local −Z.
  void add_light(const tinygltf::Light& light, const Transform& world, const std::string& context) {
    Rgb color{1, 1, 1};
    if (!light.color.empty()) {
      if (light.color.size() != 3 || !all_finite(light.color))
        fail("{}: light color must be 3 finite numbers", context);
      color = {float(light.color[0]), float(light.color[1]), float(light.color[2])};
    }
    if (!std::isfinite(light.intensity) || light.intensity < 0)
      fail("{}: light '{}' has invalid intensity {}", context, light.name, light.intensity);
    if (light.range > 0) warn_once("light range is ignored: lights fall off with the inverse square of distance");
    const Spectrum emission = RgbIlluminantSpectrum(color * float(light.intensity));
    const Vec3f position(world.point({0, 0, 0}));
    const Vec3f direction(normalize(world.vector({0, 0, -1})));
    if (light.type != "point" && !is_finite(direction))
      fail("{}: light '{}' has a degenerate direction (zero scale?)", context, light.name);
    if (light.type == "point") {
      scene_.point_lights.push_back({light.name, position, emission});
    } else if (light.type == "spot") {
      const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
      if (!(inner >= 0 && inner <= outer && outer <= kPi / 2 + 1e-6))
        fail("{}: spot light '{}' needs 0 ≤ innerConeAngle ≤ outerConeAngle ≤ π/2 (got {} and {})", context, light.name,
             inner, outer);
      scene_.spot_lights.push_back({light.name, position, direction, float(inner), float(outer), emission});
    } else if (light.type == "directional") {
      scene_.directional_lights.push_back({light.name, direction, emission});
    } else {
      warn_once(fmt::format("ignoring lights of unknown type '{}'", light.type));
    }
  }

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
