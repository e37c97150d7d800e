#pragma once
// Materials as the scene describes them (wavelength-independent): the glTF metallic-roughness
// material with its extensions' layers, and what a material has at one surface point. The BSDF it
// yields there for a path's wavelengths is make_bsdf's (make_bsdf.h).

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <variant>

#include "materials/ior.h"
#include "materials/medium.h"
#include "materials/texture.h"
#include "spectral/spectrum.h"

namespace prism {

// Pure Lambertian reflection (reference scenes and tests; glTF surfaces are PbrMaterial).
struct DiffuseMaterial {
  Spectrum reflectance = ConstantSpectrum{0.8f};
};

// A metal's measured complex index n(λ) + ik(λ), from the catalogue.
struct MeasuredMetal {
  Spectrum n, k;
  std::string catalogue;
};

// The dielectric interface of a surface: its index, and, for a closed volume (not a thin
// wall), the medium that fills it (medium.h): Beer–Lambert absorption, scattering, or neither.
struct Dielectric {
  Dielectric() : Dielectric(ConstantIor{1.5f}) {}
  explicit Dielectric(IorModel ior_model, Medium inside = {}, bool thin = false)
      : ior(std::move(ior_model)), interior(std::move(inside)), thin_walled(thin), dispersive(is_dispersive(ior)) {}

  IorModel ior;
  Medium interior;
  bool thin_walled;
  bool dispersive;  // derived from ior
};

struct ConstantSpectra;

// Where on a surface a material is evaluated: its texture coordinates and vertex colour.
struct SurfacePoint {
  std::array<Vec2f, 2> uv{};                      // TEXCOORD_0, TEXCOORD_1
  std::array<float, 4> vertex_color{1, 1, 1, 1};  // COLOR_0 (RGBA), white when absent
  Vec3f coat_normal{0, 0, 1};                     // a clear coat's own normal, in the shading frame
  // The material's colours upsampled once (World), not at every hit. Null: upsampled from the
  // inputs here.
  const ConstantSpectra* spectra = nullptr;

  bool operator==(const SurfacePoint&) const = default;
};

// A PbrMaterial's parameters at one surface point: factor × texture × vertex colour. The
// layers' are left at their neutral values when the material has no such layer.
struct SurfaceInputs {
  Rgb base_color;
  float alpha, metallic, roughness, transmission;
  bool thin_walled;
  float specular = 1;
  Rgb specular_color{1, 1, 1};
  float clearcoat = 0, clearcoat_roughness = 0;
  Rgb sheen_color{0, 0, 0};
  float sheen_roughness = 0;
  float iridescence = 0, iridescence_thickness = 0;  // nanometres
  float diffuse_transmission = 0;
  Rgb diffuse_transmission_color{1, 1, 1};
  float anisotropy = 0;   // KHR_materials_anisotropy's strength × texture B
  bool textured = false;  // some input was read from a texture (else they are the same at every point)

  bool operator==(const SurfaceInputs&) const = default;
};

// The KHR material extensions' layers of a PbrMaterial, each a factor with its textures.
struct Clearcoat {  // KHR_materials_clearcoat: a dielectric coat (index 1.5) over everything
  float factor = 0, roughness = 0;
  std::optional<Texture> texture, roughness_texture;  // linear; R × factor, G × roughness
  std::optional<Texture> normal_texture;              // tangent space, linear: the coat's own normal
  float normal_scale = 1;
};
struct Sheen {  // KHR_materials_sheen: a Charlie sheen over the base
  Rgb color{0, 0, 0};
  float roughness = 0;
  std::optional<Texture> color_texture, roughness_texture;  // sRGB RGB × color; linear A × roughness
};
struct Iridescence {  // KHR_materials_iridescence: a thin film over the base (thin_film.h)
  float factor = 0, ior = 1.3f, thickness_min = 100, thickness_max = 400;  // nanometres
  std::optional<Texture> texture, thickness_texture;                       // linear; R × factor, G: min → max
};
struct DiffuseTransmission {  // KHR_materials_diffuse_transmission: the diffuse base, partly through
  float factor = 0;
  Rgb color{1, 1, 1};
  std::optional<Texture> texture, color_texture;  // linear A × factor; sRGB RGB × color
};

// glTF's metallic–roughness material, interpreted physically (see materials/pbr_bsdf.h and
// docs/design.md, "The glTF model"):
// a metal (measured n, k, or coloured by the base colour) blended by `metallic` with a
// dielectric interface over a Lambertian base, part of which transmits (`transmission`).
struct PbrMaterial {
  Rgb base_color{1, 1, 1};
  float alpha = 1;
  float metallic = 1, roughness = 1, transmission = 0;
  float specular = 1;               // KHR_materials_specular's factor: scales the dielectric's reflectance
  Rgb specular_color{1, 1, 1};      // KHR_materials_specular's colour: scales F0 (not F90)
  bool energy_compensation = true;  // multiple scattering between microfacets added back (Turquin 2019)
  Dielectric dielectric;
  std::optional<MeasuredMetal> metal;  // replaces the base-colour metal when set
  // The base's spectral reflectance given in the file (extras "reflectance"), in place of
  // base_color, which is then white: a texture or vertex colour multiplies it as its upsampled
  // reflectance (base_spectrum).
  std::optional<Spectrum> base_reflectance;
  std::optional<Texture> base_color_texture;          // sRGB; RGB × base_color, A × alpha
  std::optional<Texture> metallic_roughness_texture;  // linear; B × metallic, G × roughness
  std::optional<Texture> transmission_texture;        // linear; R × transmission
  std::optional<Texture> thickness_texture;           // linear; G = 0 marks a thin wall
  std::optional<Texture> specular_texture;            // linear; A × specular
  std::optional<Texture> specular_color_texture;      // sRGB; RGB × specular_color
  std::optional<Clearcoat> clearcoat;
  std::optional<Sheen> sheen;
  std::optional<Iridescence> iridescence;
  std::optional<DiffuseTransmission> diffuse_transmission;
  // KHR_materials_anisotropy: the roughness along the direction of anisotropy rises to
  // mix(α, 1, strength²) (α across it). The direction is the mesh tangent turned by the rotation
  // (towards the bitangent), or the texture's RG direction in tangent space turned so; the
  // texture's B multiplies the strength. See anisotropy_direction() and World::interaction.
  float anisotropy_strength = 0;
  Vec2f anisotropy_rotation{1, 0};  // (cos, sin) of the extension's anisotropyRotation: found once, not per hit
  std::optional<Texture> anisotropy_texture;  // linear; RG direction in [−1, 1], B strength

  SurfaceInputs inputs(const SurfacePoint& at) const;
  // Whether inputs() reads a texture, so that its inputs vary over the surface (a cost hint for
  // BsdfCache, which relies on SurfaceInputs::textured: a texture missing here costs time, never
  // correctness).
  bool textured() const;
  bool anisotropic() const { return anisotropy_strength > 0; }
  // Whether some point of it may need the extensions' layered BSDF (LayeredBsdf, make_bsdf): a
  // clear coat, sheen, thin film, diffuse transmission or specular colour.
  bool layered() const {
    return clearcoat || sheen || iridescence || diffuse_transmission || specular_color != Rgb{1, 1, 1} ||
           specular_color_texture;
  }
  // The direction of anisotropy in tangent space (x along the tangent, y the bitangent), unit.
  Vec2f anisotropy_direction(const SurfacePoint& at) const;
  // The base's reflectance at a path's wavelengths, where the inputs are `base_color`
  // (inputs(at).base_color: factor × texture × vertex colour) and `upsampled` is that colour as a
  // spectrum: the file's spectrum, times `upsampled` where a texture or vertex colour varies it
  // (base_color not white), else `upsampled` alone.
  template <int N>
  SampledSpectrum<N> base_spectrum(Rgb base_color, const RgbAlbedoSpectrum& upsampled,
                                   const SampledWavelengths<N>& lambda) const {
    if (!base_reflectance) return upsampled(lambda);
    SampledSpectrum<N> r = sample(*base_reflectance, lambda);
    if (base_color != Rgb{1, 1, 1}) r *= upsampled(lambda);
    return r;
  }

  static PbrMaterial glass(Dielectric d, float roughness = 0);
  static PbrMaterial metal_of(MeasuredMetal m, float roughness = 0);
  static PbrMaterial metal_of(Rgb color, float roughness = 0);
  static PbrMaterial plastic(Rgb color, float roughness, float ior = 1.5f);  // metallic 0, opaque
};

// A PbrMaterial's colours as spectra, each where no texture varies it (the base colour's is used
// where no vertex colour varies it either): upsampled once per material, evaluated at each hit.
struct ConstantSpectra {
  ConstantSpectra() = default;  // none
  explicit ConstantSpectra(const PbrMaterial& m);
  std::optional<RgbAlbedoSpectrum> base_color, sheen_color, diffuse_transmission_color;
  std::optional<RgbUnboundedSpectrum> specular_color;
};

using MaterialKind = std::variant<DiffuseMaterial, PbrMaterial>;

enum class AlphaMode { opaque, mask, blend };

struct Material {
  std::string name;
  MaterialKind kind;
  std::optional<Spectrum> emission{};  // emitted radiance; front face only unless double_sided
  bool double_sided = false;
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;
  std::optional<Texture> normal_texture{};  // tangent space, linear
  float normal_scale = 1;
  std::optional<Texture> emission_texture{};  // sRGB; multiplies the emission's RGB
  Rgb emission_rgb{0, 0, 0};                  // emissiveFactor × strength (for a textured emission)
  // Whether `emission` is a spectrum the file gives (extras "emission"), of the luminance of
  // emission_rgb, rather than emission_rgb upsampled: a texture then scales its luminance.
  bool spectral_emission = false;

  // Emitted radiance at a point (with the texture, if any), or nothing: RGB emission only.
  std::optional<Spectrum> emission_at(const SurfacePoint& at) const;
  // A spectral emission's scale at a point: the luminance of emission_rgb × texel over that of
  // emission_rgb (1 without a texture).
  float emission_scale(const SurfacePoint& at) const;
  // Emitted radiance for the path's wavelengths; 0 where the material does not emit. (Which side
  // emits is the caller's check: AreaLight::emits_towards.)
  template <int N>
  SampledSpectrum<N> emitted(const SurfacePoint& at, const SampledWavelengths<N>& lambda) const {
    if (!emission_texture) return emission ? sample(*emission, lambda) : SampledSpectrum<N>(0.f);
    if (spectral_emission) return sample(*emission, lambda) * emission_scale(at);
    const auto e = emission_at(at);
    return e ? sample(*e, lambda) : SampledSpectrum<N>(0.f);
  }
  // Opacity at a point: PbrMaterial alpha × texture × vertex colour; 1 when opaque.
  float opacity(const SurfacePoint& at) const;
  // The share of an alpha BLEND surface that is there (it scatters and emits that much of its
  // light; the rest is a hole), in [0, 1]; 1 unless BLEND.
  float blend_opacity(const SurfacePoint& at) const;
  // The share of the surface that is there at a point, for any alpha mode: under MASK 1 or 0 (its
  // opacity against the cutoff), under BLEND blend_opacity, 1 when opaque.
  float coverage(const SurfacePoint& at) const;

  // Whether light can pass through the surface anywhere (transmission or diffuse transmission);
  // otherwise it only reflects, into the side the light comes from.
  bool transmits() const {
    const auto* p = std::get_if<PbrMaterial>(&kind);
    return p && (p->transmission > 0 || (p->diffuse_transmission && p->diffuse_transmission->factor > 0));
  }

  // The surface's dielectric interface, if light can pass it (for nested media and dispersion).
  const Dielectric* dielectric() const {
    const auto* p = std::get_if<PbrMaterial>(&kind);
    return p && p->metallic < 1 && p->transmission > 0 ? &p->dielectric : nullptr;
  }
};

// Whether the index ratio at a surface of m varies with λ, so that refraction sends each
// wavelength its own way.
inline bool disperses(const Material& m, const Dielectric* front) {
  const Dielectric* d = m.dielectric();
  return d && (d->dispersive || (front && front->dispersive));
}

}  // namespace prism
