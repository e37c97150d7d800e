// glTF materials: the metallic–roughness model with the KHR material extensions Prism honours,
// textures (with KHR_texture_transform) and their images, decoded on first use.

#include <algorithm>
#include <cmath>

#include "core/base/log.h"
#include "core/scene/gltf_import.h"

namespace prism {

Material GltfLoader::convert_material(const tinygltf::Material& m, int index) {
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
  // The thickness only marks thin walls, where its G is 0 (PbrMaterial::inputs): a texture with no
  // such texel marks none (bilinear filtering of positive texels stays positive), and is dropped
  // rather than looked up at every hit.
  if (surface_model.thickness_texture && !surface_model.thickness_texture->image->any_zero(1))
    surface_model.thickness_texture.reset();
  if (m.extensions.count("KHR_materials_pbrSpecularGlossiness")) apply_spec_gloss(m, surface_model, context);
  surface_model.anisotropy_texture = extension_texture(m, "KHR_materials_anisotropy", "anisotropyTexture", context);
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
  if (ef.size() != 3 || !all_finite(ef) || *std::min_element(ef.begin(), ef.end()) < 0)
    fail("{}: {}: emissiveFactor must be 3 finite numbers ≥ 0", file_, context);
  double strength = 1;
  if (const auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end()) {
    const auto& v = it->second.Get("emissiveStrength");
    if (v.IsNumber()) strength = v.GetNumberAsDouble();
    if (!std::isfinite(strength) || strength < 0)
      fail("{}: {}: emissiveStrength must be a non-negative number", file_, context);
  }
  out.emission_rgb = clamp_emission({ef[0] * strength, ef[1] * strength, ef[2] * strength}, context);
  if (out.emission_rgb.max() > 0) {
    out.emission = RgbIlluminantSpectrum(out.emission_rgb);
    out.emission_texture =
        texture(m.emissiveTexture.index, m.emissiveTexture.texCoord, m.emissiveTexture.extensions, context);
  }
  material_extras(m, index, out, context);
  if (m.extensions.count("KHR_materials_unlit")) make_unlit(out);
  return out;
}

// --- textures -----------------------------------------------------------------------------

// The decoded image of glTF image `index` (decoded once, on first use).
std::shared_ptr<const Image> GltfLoader::image(int index, const std::string& context) {
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
std::optional<Texture> GltfLoader::texture(int index, int texcoord, const tinygltf::ExtensionMap& extensions,
                                           const std::string& context) {
  if (index < 0) return std::nullopt;
  check_index(index, model_.textures, "texture", context);
  const tinygltf::Texture& t = model_.textures[index];
  Texture out;
  out.image = image(texture_source(t, index, context), context);
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
std::optional<Texture> GltfLoader::extension_texture(const tinygltf::Material& m, const char* extension,
                                                     const char* field, const std::string& context) {
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

// glTF's metallic-roughness parameters with the KHR extensions Prism honours (the material's
// extras, catalogue materials and spectra, are read after: gltf_extras.cpp).
PbrMaterial GltfLoader::surface(const tinygltf::Material& m, Rgb base, const std::string& context) {
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
  // An RGB factor of extension `ext`, each channel in [lo, hi].
  const auto color = [&](const char* ext, const char* field, Rgb fallback, double lo, double hi) {
    const auto it = m.extensions.find(ext);
    if (it == m.extensions.end() || !it->second.Has(field)) return fallback;
    const auto& v = it->second.Get(field);
    Rgb c;
    for (int i = 0; i < 3; ++i) {
      const double x = v.IsArray() && v.ArrayLen() == 3 && v.Get(i).IsNumber() ? v.Get(i).GetNumberAsDouble() : -1;
      if (!(x >= lo && x <= hi))
        fail("{}: {}: {}.{} must hold 3 numbers in [{}, {}]", file_, context, ext, field, lo, hi);
      c[i] = float(x);
    }
    return c;
  };
  const auto has = [&](const char* ext) { return m.extensions.count(ext) > 0; };
  const auto tex = [&](const char* ext, const char* field) { return extension_texture(m, ext, field, context); };

  p.specular = float(number("KHR_materials_specular", "specularFactor", 1, 0, 1));
  p.specular_texture = tex("KHR_materials_specular", "specularTexture");
  // Values above 1 are allowed (F0 is capped at 1 after the product).
  p.specular_color = color("KHR_materials_specular", "specularColorFactor", {1, 1, 1}, 0, 1e6);
  p.specular_color_texture = tex("KHR_materials_specular", "specularColorTexture");
  if (has("KHR_materials_clearcoat")) {
    const char* ext = "KHR_materials_clearcoat";
    Clearcoat c;
    c.factor = float(number(ext, "clearcoatFactor", 0, 0, 1));
    c.roughness = float(number(ext, "clearcoatRoughnessFactor", 0, 0, 1));
    c.texture = tex(ext, "clearcoatTexture");
    c.roughness_texture = tex(ext, "clearcoatRoughnessTexture");
    c.normal_texture = tex(ext, "clearcoatNormalTexture");
    if (const auto& info = m.extensions.at(ext).Get("clearcoatNormalTexture"); c.normal_texture && info.Has("scale"))
      c.normal_scale = float(info.Get("scale").GetNumberAsDouble());
    if (c.factor > 0) p.clearcoat = std::move(c);
  }
  if (has("KHR_materials_sheen")) {
    const char* ext = "KHR_materials_sheen";
    Sheen sh;
    sh.color = color(ext, "sheenColorFactor", {0, 0, 0}, 0, 1);
    sh.roughness = float(number(ext, "sheenRoughnessFactor", 0, 0, 1));
    sh.color_texture = tex(ext, "sheenColorTexture");
    sh.roughness_texture = tex(ext, "sheenRoughnessTexture");
    if (sh.color.max() > 0) p.sheen = std::move(sh);
  }
  if (has("KHR_materials_iridescence")) {
    const char* ext = "KHR_materials_iridescence";
    Iridescence ir;
    ir.factor = float(number(ext, "iridescenceFactor", 0, 0, 1));
    ir.ior = float(number(ext, "iridescenceIor", 1.3, 1, 10));
    ir.thickness_min = float(number(ext, "iridescenceThicknessMinimum", 100, 0, 1e5));
    ir.thickness_max = float(number(ext, "iridescenceThicknessMaximum", 400, 0, 1e5));
    ir.texture = tex(ext, "iridescenceTexture");
    ir.thickness_texture = tex(ext, "iridescenceThicknessTexture");
    if (ir.factor > 0) p.iridescence = std::move(ir);
  }
  if (has("KHR_materials_diffuse_transmission")) {
    const char* ext = "KHR_materials_diffuse_transmission";
    DiffuseTransmission d;
    d.factor = float(number(ext, "diffuseTransmissionFactor", 0, 0, 1));
    d.color = color(ext, "diffuseTransmissionColorFactor", {1, 1, 1}, 0, 1);
    d.texture = tex(ext, "diffuseTransmissionTexture");
    d.color_texture = tex(ext, "diffuseTransmissionColorTexture");
    if (d.factor > 0) p.diffuse_transmission = std::move(d);
  }
  p.anisotropy_strength = float(number("KHR_materials_anisotropy", "anisotropyStrength", 0, 0, 1));
  const float rotation = float(number("KHR_materials_anisotropy", "anisotropyRotation", 0, -1e6, 1e6));
  p.anisotropy_rotation = {std::cos(rotation), std::sin(rotation)};

  IorModel ior_model = ConstantIor{float(number("KHR_materials_ior", "ior", 1.5, 1, 1e3))};
  if (const double dispersion = number("KHR_materials_dispersion", "dispersion", 0, 0, 1e6); dispersion > 0) {
    // KHR_materials_dispersion: dispersion = 20 / V_d.
    ior_model = AbbeIor{std::get<ConstantIor>(ior_model).n, float(20 / dispersion)};
  }
  // KHR_materials_volume: thickness 0 is a thin wall; otherwise a closed volume whose white light
  // turns into attenuationColor at attenuationDistance: σ_a(λ) = −ln T(λ) / d with T the colour
  // upsampled as a reflectance (RgbAbsorptionSpectrum), not −ln per RGB channel upsampled, which
  // misses the colour by up to 3%.
  const double thickness = number("KHR_materials_volume", "thicknessFactor", 0, 0, 1e30);
  const double distance = number("KHR_materials_volume", "attenuationDistance", kInfinity, 0, kInfinity);
  if (distance == 0) fail("{}: {}: KHR_materials_volume.attenuationDistance must be > 0", file_, context);
  std::optional<Spectrum> absorption;
  if (thickness > 0 && std::isfinite(distance)) {
    Rgb color;
    const auto json = m.extensions.at("KHR_materials_volume").Get("attenuationColor");
    for (int c = 0; c < 3; ++c) {
      const double a = json.IsArray() && json.ArrayLen() == 3 ? json.Get(c).GetNumberAsDouble() : 1.0;
      if (!(a >= 0 && a <= 1)) fail("{}: {}: attenuationColor must hold 3 numbers in [0, 1]", file_, context);
      color[c] = float(a);
    }
    if (std::min({color.r, color.g, color.b}) < 1) absorption = RgbAbsorptionSpectrum(color, float(distance));
  }
  Medium interior{.sigma_a = std::move(absorption)};
  // KHR_materials_volume_scatter (a draft, read as it stands; KHR_materials_scatter may replace it):
  // the attenuation above is then the extinction σ_t, of which the share ρ_ss(multiscatterColor)
  // scatters (medium_of_albedo), by a Henyey–Greenstein lobe of asymmetry scatterAnisotropy.
  if (has("KHR_materials_volume_scatter") && interior.sigma_a && thickness > 0) {
    const char* ext = "KHR_materials_volume_scatter";
    const Rgb multiscatter = color(ext, "multiscatterColor", {0, 0, 0}, 0, 1);
    const float g = float(number(ext, "scatterAnisotropy", 0, -0.999, 0.999));
    if (multiscatter != Rgb{0, 0, 0})
      interior = medium_of_albedo(*interior.sigma_a, RgbAlbedoSpectrum(multiscatter), g);
  }
  p.dielectric = Dielectric(std::move(ior_model), std::move(interior), thickness == 0);
  return p;
}

// Emission beyond kMaxEmission (legal glTF, e.g. emissiveStrength 1e38) is clamped with a warning.
Rgb GltfLoader::clamp_emission(const std::array<double, 3>& rgb, const std::string& context) {
  Rgb out;
  for (int c = 0; c < 3; ++c) {
    if (rgb[c] > kMaxEmission)
      warn_once(fmt::format("{}: emission or intensity {:g} clamped to {:g}",
                            context.rfind(file_ + ": ", 0) == 0 ? context.substr(file_.size() + 2) : context, rgb[c],
                            kMaxEmission));
    out[c] = float(std::min(rgb[c], double(kMaxEmission)));
  }
  return out;
}

uint32_t GltfLoader::material_index(int gltf_material, const std::string& context) {
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

}  // namespace prism
