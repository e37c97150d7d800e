#include "materials/material.h"

namespace prism {

ConstantSpectra::ConstantSpectra(const PbrMaterial& m) {
  if (!m.base_color_texture) base_color.emplace(m.base_color);
  if (!m.specular_color_texture && m.specular_color != Rgb{1, 1, 1}) specular_color.emplace(m.specular_color);
  if (m.sheen && !m.sheen->color_texture) sheen_color.emplace(m.sheen->color);
  if (m.diffuse_transmission && !m.diffuse_transmission->color_texture)
    diffuse_transmission_color.emplace(m.diffuse_transmission->color);
}

SurfaceInputs PbrMaterial::inputs(const SurfacePoint& at) const {
  SurfaceInputs in{base_color, alpha, metallic, roughness, transmission, dielectric.thin_walled};
  const auto texel = [&](const std::optional<Texture>& t, bool srgb) {
    in.textured = true;
    return t->lookup(at.uv[t->texcoord], srgb);
  };
  if (base_color_texture) {
    const auto c = texel(base_color_texture, true);
    in.base_color = {in.base_color.r * c[0], in.base_color.g * c[1], in.base_color.b * c[2]};
    in.alpha *= c[3];
  }
  for (int i = 0; i < 3; ++i) in.base_color[i] *= at.vertex_color[i];
  in.alpha *= at.vertex_color[3];
  if (metallic_roughness_texture) {
    const auto t = texel(metallic_roughness_texture, false);
    in.roughness *= t[1];
    in.metallic *= t[2];
  }
  if (transmission_texture) in.transmission *= texel(transmission_texture, false)[0];
  if (thickness_texture && texel(thickness_texture, false)[1] == 0) in.thin_walled = true;
  const auto scale_rgb = [&](Rgb& c, const std::optional<Texture>& t) {
    if (!t) return;
    const auto v = texel(t, true);
    for (int i = 0; i < 3; ++i) c[i] *= v[i];
  };
  in.specular = specular;
  if (specular_texture) in.specular *= texel(specular_texture, false)[3];
  in.specular_color = specular_color;
  scale_rgb(in.specular_color, specular_color_texture);
  if (clearcoat) {
    in.clearcoat = clearcoat->factor;
    in.clearcoat_roughness = clearcoat->roughness;
    if (clearcoat->texture) in.clearcoat *= texel(clearcoat->texture, false)[0];
    if (clearcoat->roughness_texture) in.clearcoat_roughness *= texel(clearcoat->roughness_texture, false)[1];
  }
  if (sheen) {
    in.sheen_color = sheen->color;
    scale_rgb(in.sheen_color, sheen->color_texture);
    in.sheen_roughness = sheen->roughness;
    if (sheen->roughness_texture) in.sheen_roughness *= texel(sheen->roughness_texture, false)[3];
  }
  if (iridescence) {
    in.iridescence = iridescence->factor;
    if (iridescence->texture) in.iridescence *= texel(iridescence->texture, false)[0];
    const float t = iridescence->thickness_texture ? texel(iridescence->thickness_texture, false)[1] : 1.f;
    in.iridescence_thickness = lerp(t, iridescence->thickness_min, iridescence->thickness_max);
  }
  if (diffuse_transmission) {
    in.diffuse_transmission = diffuse_transmission->factor;
    if (diffuse_transmission->texture) in.diffuse_transmission *= texel(diffuse_transmission->texture, false)[3];
    in.diffuse_transmission_color = diffuse_transmission->color;
    scale_rgb(in.diffuse_transmission_color, diffuse_transmission->color_texture);
  }
  in.anisotropy = anisotropy_strength;
  if (anisotropic() && anisotropy_texture) in.anisotropy *= texel(anisotropy_texture, false)[2];
  return in;
}

bool PbrMaterial::textured() const {
  return base_color_texture || metallic_roughness_texture || transmission_texture || thickness_texture ||
         specular_texture || specular_color_texture ||
         (clearcoat && (clearcoat->texture || clearcoat->roughness_texture)) ||
         (sheen && (sheen->color_texture || sheen->roughness_texture)) ||
         (iridescence && (iridescence->texture || iridescence->thickness_texture)) ||
         (diffuse_transmission && (diffuse_transmission->texture || diffuse_transmission->color_texture)) ||
         (anisotropic() && anisotropy_texture);
}

Vec2f PbrMaterial::anisotropy_direction(const SurfacePoint& at) const {
  Vec2f d(1, 0);
  if (anisotropy_texture) {
    const auto t = anisotropy_texture->lookup(at.uv[anisotropy_texture->texcoord], false);
    const Vec2f texel(2 * t[0] - 1, 2 * t[1] - 1);
    const float len = std::sqrt(texel.x * texel.x + texel.y * texel.y);
    if (len > 0) d = Vec2f(texel.x / len, texel.y / len);
  }
  const float c = anisotropy_rotation.x, s = anisotropy_rotation.y;
  return {c * d.x - s * d.y, s * d.x + c * d.y};
}

std::optional<Spectrum> Material::emission_at(const SurfacePoint& at) const {
  if (!emission_texture) return emission;
  const auto c = emission_texture->lookup(at.uv[emission_texture->texcoord], true);
  const Rgb rgb{emission_rgb.r * c[0], emission_rgb.g * c[1], emission_rgb.b * c[2]};
  if (rgb.max() <= 0) return std::nullopt;
  return RgbIlluminantSpectrum(rgb);
}

float Material::emission_scale(const SurfacePoint& at) const {
  if (!emission_texture) return 1.f;
  const auto c = emission_texture->lookup(at.uv[emission_texture->texcoord], true);
  const float full = luminance(emission_rgb);
  return full > 0 ? luminance({emission_rgb.r * c[0], emission_rgb.g * c[1], emission_rgb.b * c[2]}) / full : 0.f;
}

float Material::opacity(const SurfacePoint& at) const {
  const auto* p = std::get_if<PbrMaterial>(&kind);
  if (alpha_mode == AlphaMode::opaque || !p) return 1.f;
  const float a = p->alpha * at.vertex_color[3];
  return p->base_color_texture ? a * p->base_color_texture->lookup(at.uv[p->base_color_texture->texcoord], true)[3] : a;
}

float Material::blend_opacity(const SurfacePoint& at) const {
  if (alpha_mode != AlphaMode::blend) return 1.f;
  const float a = opacity(at);
  return a < 1 ? std::max(a, 0.f) : 1.f;  // a NaN (from a hostile vertex colour) is opaque, as World::cut_away has it
}

float Material::coverage(const SurfacePoint& at) const {
  if (alpha_mode == AlphaMode::mask) return opacity(at) < alpha_cutoff ? 0.f : 1.f;
  return blend_opacity(at);
}

PbrMaterial PbrMaterial::glass(Dielectric d, float roughness) {
  PbrMaterial m;
  m.metallic = 0;
  m.roughness = roughness;
  m.transmission = 1;
  m.dielectric = std::move(d);
  return m;
}

PbrMaterial PbrMaterial::metal_of(MeasuredMetal metal, float roughness) {
  PbrMaterial m;
  m.roughness = roughness;
  m.metal = std::move(metal);
  return m;
}

PbrMaterial PbrMaterial::metal_of(Rgb color, float roughness) {
  PbrMaterial m;
  m.base_color = color;
  m.roughness = roughness;
  return m;
}

PbrMaterial PbrMaterial::plastic(Rgb color, float roughness, float ior_value) {
  PbrMaterial m;
  m.base_color = color;
  m.metallic = 0;
  m.roughness = roughness;
  m.dielectric = Dielectric(ConstantIor{ior_value});
  return m;
}

}  // namespace prism
