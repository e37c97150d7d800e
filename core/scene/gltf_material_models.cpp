// Two material models older files still use, mapped onto Prism's: KHR_materials_unlit (the
// base colour emitted, nothing scattered) and the archived KHR_materials_pbrSpecularGlossiness
// (converted to metallic–roughness, texel by texel when textured).

#include <cmath>

#include "core/base/log.h"
#include "core/scene/gltf_import.h"

namespace prism {

namespace {

// --- specular–glossiness to metallic–roughness ----------------------------------------------
// The conversion of the extension's own sample code (KhronosGroup/glTF, extensions/2.0/Archived/
// KHR_materials_pbrSpecularGlossiness/examples/convert-between-workflows, by Microsoft's Babylon
// team): a dielectric reflects F0 = 0.04; the metallic fraction solves the quadratic that keeps
// the perceived brightness of diffuse + specular; roughness = 1 − glossiness.

constexpr float kDielectricF0 = 0.04f;

float perceived_brightness(Rgb c) { return std::sqrt(0.299f * c.r * c.r + 0.587f * c.g * c.g + 0.114f * c.b * c.b); }

float solve_metallic(float diffuse, float specular, float one_minus_specular_strength) {
  if (specular < kDielectricF0) return 0;
  const float a = kDielectricF0;
  const float b = diffuse * one_minus_specular_strength / (1 - kDielectricF0) + specular - 2 * kDielectricF0;
  const float c = kDielectricF0 - specular;
  const float d = std::max(b * b - 4 * a * c, 0.f);
  return std::clamp((-b + std::sqrt(d)) / (2 * a), 0.f, 1.f);
}

struct MetalRough {
  Rgb base_color;
  float metallic, roughness;
};

MetalRough metal_rough(Rgb diffuse, Rgb specular, float glossiness) {
  const float one_minus_specular_strength = 1 - specular.max();
  const float metallic =
      solve_metallic(perceived_brightness(diffuse), perceived_brightness(specular), one_minus_specular_strength);
  constexpr float eps = 1e-6f;
  Rgb base;
  for (int i = 0; i < 3; ++i) {
    const float from_diffuse =
        diffuse[i] * one_minus_specular_strength / (1 - kDielectricF0) / std::max(1 - metallic, eps);
    const float from_specular = (specular[i] - kDielectricF0 * (1 - metallic)) / std::max(metallic, eps);
    const float t = metallic * metallic;
    base[i] = std::clamp(from_diffuse + t * (from_specular - from_diffuse), 0.f, 1.f);
  }
  return {base, metallic, std::clamp(1 - glossiness, 0.f, 1.f)};
}

uint8_t to_srgb8(float linear) {
  const float c = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
  return uint8_t(std::lround(std::clamp(c, 0.f, 1.f) * 255));
}

}  // namespace

// KHR_materials_unlit: what the file's author saw is the base colour (× texture), whatever the
// lighting. Prism makes it the surface's emitted radiance (an emitter like any other, which also
// lights its surroundings) and lets it scatter nothing; alpha still cuts the surface away.
void GltfLoader::make_unlit(Material& out) {
  auto& p = std::get<PbrMaterial>(out.kind);
  out.emission_rgb = p.base_color;
  out.emission =
      out.emission_rgb.max() > 0 ? std::optional<Spectrum>(RgbIlluminantSpectrum(p.base_color)) : std::nullopt;
  out.emission_texture = p.base_color_texture;
  out.normal_texture.reset();
  p.base_color = {0, 0, 0};
  p.metallic = p.transmission = p.specular = 0;
  p.metallic_roughness_texture.reset();
  p.transmission_texture.reset();
}

// KHR_materials_pbrSpecularGlossiness converted by metal_rough above: factors alone convert
// once; with textures, the converted parameters are baked into a base-colour and a
// metallic–roughness image (at the larger of the two images' sizes, sampled with each
// texture's own sampler), which then carry the diffuse texture's coordinates and transform.
void GltfLoader::apply_spec_gloss(const tinygltf::Material& m, PbrMaterial& p, const std::string& context) {
  const tinygltf::Value& ext = m.extensions.at("KHR_materials_pbrSpecularGlossiness");
  const auto factor = [&](const char* key, std::vector<double> fallback) {
    if (!ext.Has(key)) return fallback;
    const auto& v = ext.Get(key);
    std::vector<double> out;
    for (size_t i = 0; v.IsArray() && i < v.ArrayLen(); ++i)
      out.push_back(v.Get(int(i)).IsNumber() ? v.Get(int(i)).GetNumberAsDouble() : std::nan(""));
    if (v.IsNumber()) out.push_back(v.GetNumberAsDouble());
    if (out.size() != fallback.size() || !all_finite(out))
      fail("{}: {}: KHR_materials_pbrSpecularGlossiness.{} must be {} finite numbers", file_, context, key,
           fallback.size());
    return out;
  };
  const auto diffuse_factor = factor("diffuseFactor", {1, 1, 1, 1});
  const auto specular_factor = factor("specularFactor", {1, 1, 1});
  const float glossiness_factor = float(factor("glossinessFactor", {1})[0]);
  const Rgb diffuse{float(diffuse_factor[0]), float(diffuse_factor[1]), float(diffuse_factor[2])};
  const Rgb specular{float(specular_factor[0]), float(specular_factor[1]), float(specular_factor[2])};
  p.alpha = std::clamp(float(diffuse_factor[3]), 0.f, 1.f);
  const auto diffuse_texture = extension_texture(m, "KHR_materials_pbrSpecularGlossiness", "diffuseTexture", context);
  const auto sg_texture =
      extension_texture(m, "KHR_materials_pbrSpecularGlossiness", "specularGlossinessTexture", context);
  p.metallic_roughness_texture.reset();
  if (!diffuse_texture && !sg_texture) {
    const MetalRough mr = metal_rough(diffuse, specular, glossiness_factor);
    p.base_color = mr.base_color, p.metallic = mr.metallic, p.roughness = mr.roughness;
    p.base_color_texture.reset();
    return;
  }
  const Texture& layout = diffuse_texture ? *diffuse_texture : *sg_texture;
  if (diffuse_texture && sg_texture &&
      (diffuse_texture->texcoord != sg_texture->texcoord ||
       diffuse_texture->transform.offset != sg_texture->transform.offset ||
       diffuse_texture->transform.scale != sg_texture->transform.scale ||
       diffuse_texture->transform.rotation != sg_texture->transform.rotation))
    warn_once("specular-glossiness textures with different coordinates are baked with the diffuse texture's");
  const int w =
      std::max(diffuse_texture ? diffuse_texture->image->width() : 1, sg_texture ? sg_texture->image->width() : 1);
  const int h =
      std::max(diffuse_texture ? diffuse_texture->image->height() : 1, sg_texture ? sg_texture->image->height() : 1);
  std::vector<uint8_t> base(size_t(w) * h * 4), metal_rough_texels(size_t(w) * h * 4, 255);
  const auto untransformed = [](Texture t) {
    t.transform = {};
    return t;
  };
  const std::optional<Texture> d = diffuse_texture ? std::optional(untransformed(*diffuse_texture)) : std::nullopt;
  const std::optional<Texture> s = sg_texture ? std::optional(untransformed(*sg_texture)) : std::nullopt;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec2f uv((x + 0.5f) / float(w), (y + 0.5f) / float(h));
      const auto dt = d ? d->lookup(uv, true) : std::array<float, 4>{1, 1, 1, 1};
      // The specular colour is sRGB-encoded, the glossiness (alpha) linear.
      const auto st = s ? s->lookup(uv, true) : std::array<float, 4>{1, 1, 1, 1};
      const MetalRough mr =
          metal_rough({diffuse.r * dt[0], diffuse.g * dt[1], diffuse.b * dt[2]},
                      {specular.r * st[0], specular.g * st[1], specular.b * st[2]}, glossiness_factor * st[3]);
      uint8_t* b = &base[(size_t(y) * w + x) * 4];
      for (int c = 0; c < 3; ++c) b[c] = to_srgb8(mr.base_color[c]);
      b[3] = uint8_t(std::lround(std::clamp(dt[3], 0.f, 1.f) * 255));
      uint8_t* mrt = &metal_rough_texels[(size_t(y) * w + x) * 4];
      mrt[1] = uint8_t(std::lround(mr.roughness * 255));
      mrt[2] = uint8_t(std::lround(mr.metallic * 255));
    }
  Texture base_texture = layout, mr_texture = layout;
  base_texture.image = std::make_shared<const Image>(w, h, std::move(base));
  mr_texture.image = std::make_shared<const Image>(w, h, std::move(metal_rough_texels));
  p.base_color_texture = base_texture;
  p.metallic_roughness_texture = mr_texture;
  p.base_color = {1, 1, 1};
  p.metallic = p.roughness = 1;
}

}  // namespace prism
