#pragma once
// Materials as the scene describes them (wavelength-independent), and the BSDF a material
// yields at one hit for one path's wavelengths.

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <variant>

#include "materials/bsdf.h"
#include "materials/ior.h"
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
// wall), the Beer–Lambert absorption coefficient σ_a(λ) of its interior, per scene unit.
struct Dielectric {
  Dielectric() : Dielectric(ConstantIor{1.5f}) {}
  explicit Dielectric(IorModel ior_model, std::optional<Spectrum> sigma_a = {}, bool thin = false)
      : ior(std::move(ior_model)), absorption(std::move(sigma_a)), thin_walled(thin), dispersive(is_dispersive(ior)) {}

  IorModel ior;
  std::optional<Spectrum> absorption;
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

// glTF's metallic–roughness material, interpreted physically (see pbr_bsdf.h and the README):
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
  std::optional<MeasuredMetal> metal;                 // replaces the base-colour metal when set
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
  // LastBsdf, which relies on SurfaceInputs::textured: a texture missing here costs time, never
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

  // Emitted radiance at a point (with the texture, if any), or nothing.
  std::optional<Spectrum> emission_at(const SurfacePoint& at) const;
  // The same for the path's wavelengths; 0 where the material does not emit. (Which side emits is
  // the caller's check: AreaLight::emits_towards.)
  template <int N>
  SampledSpectrum<N> emitted(const SurfacePoint& at, const SampledWavelengths<N>& lambda) const {
    if (!emission_texture) return emission ? sample(*emission, lambda) : SampledSpectrum<N>(0.f);
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

// Each lane's relative index η'_λ whose exact normal-incidence reflectance is that of η times c_λ
// (at most 1): KHR_materials_specular's coloured F0, on η's side of 1. The index η ≥ 1 of
// reflectance F0 = ((η − 1)/(η + 1))² is (1 + √F0)/(1 − √F0) (F0 = 1: η → ∞). Two loops over the
// lanes, each run on all lanes at once (in one, GCC turns the clamp's constant ends into branches
// and leaves the lanes one by one). The clamp's max with 0 repeats the one inside it, but GCC keeps
// the loop vector code only with it (without: make_bsdf +0.05 M instructions per spp on lobes_all).
template <int N>
SampledSpectrum<N> ior_with_scaled_f0(float eta, const SampledSpectrum<N>& c) {
  const float f0 = sqr((eta - 1) / (eta + 1));
  SampledSpectrum<N> root, scaled;
  for (int i = 0; i < N; ++i) root[i] = std::sqrt(std::min(std::max(f0 * std::max(c[i], 0.f), 0.f), 0.9999f));
  for (int i = 0; i < N; ++i) {
    const float s = (1 + root[i]) / (1 - root[i]);
    scaled[i] = eta < 1 ? 1 / s : s;
  }
  return scaled;
}

// Gulbrandsen's metal (2014, "Artist Friendly Metallic Fresnel", JCGT 3(4)) of normal-incidence
// reflectance r < 1 and edge tint g ∈ [0, 1]: n blended between (1 − r)/(1 + r) and
// (1 + √r)/(1 − √r) by g, and the k that gives F0 = r, k² = (r (n + 1)² − (n − 1)²) / (1 − r).
inline std::array<float, 2> gulbrandsen_nk(float r, float g) {
  const float sr = std::sqrt(r);
  const float n = g * (1 - r) / (1 + r) + (1 - g) * (1 + sr) / (1 - sr);
  return {n, std::sqrt(std::max((r * sqr(n + 1) - sqr(n - 1)) / (1 - r), 0.f))};
}

// The edge tints g(r) with which Gulbrandsen's metal of reflectance r reflects as much light in
// total as glTF's reference metal (Schlick, F0 = r), at r = 0, 0.01, …, 1 (built on first use).
const std::array<float, 101>& schlick_matched_edge_tints();

// Each lane's n, k of a metal whose normal-incidence reflectance is r_λ: Gulbrandsen's, with the
// edge tint that gives the directional albedo of glTF's reference metal. Measured metals in the
// visible sit close to it (edge tints 0.9-1 for Cu, Al, Ag, Au); the Fresnel formula stays exact.
// Two loops over the lanes, each run on all lanes at once (vector code): in one, GCC turns the
// clamp's constant ends into branches and leaves the lanes one by one.
template <int N>
struct MetalIndex {
  SampledSpectrum<N> n, k;
};
template <int N>
MetalIndex<N> metal_nk_from_reflectance(const SampledSpectrum<N>& reflectance) {
  const std::array<float, 101>& tint = schlick_matched_edge_tints();
  std::array<float, N> r;
  // r < 1 keeps k finite; NaN becomes 0 (std::max(0, NaN) is 0), so the table is never read outside.
  for (int i = 0; i < N; ++i) r[i] = std::max(0.f, std::min(reflectance[i], 0.999f));
  MetalIndex<N> m;
  for (int i = 0; i < N; ++i) {
    const float x = r[i] * 100;
    const int j = int(x);  // ≤ 99
    const auto nk = gulbrandsen_nk(r[i], tint[j] + (x - float(j)) * (tint[j + 1] - tint[j]));
    m.n[i] = nk[0], m.k[i] = nk[1];
  }
  return m;
}

// The BSDF of material m for the path's wavelengths. `front` is the dielectric on the front
// (normal) side of the surface, or nullptr for vacuum. Where the index ratio varies with λ, every
// lane refracts at the hero's (lane 0's) index, so only lane 0 is right: the path tracer takes
// such a material's lanes one by one (DispersiveBsdf), the bidirectional integrators keep the
// hero alone (make_hero_bsdf).
template <int N>
Bsdf<N> make_bsdf(const Material& m, const SurfacePoint& at, const SampledWavelengths<N>& lambda,
                  const Dielectric* front) {
  if (const auto* d = std::get_if<DiffuseMaterial>(&m.kind)) return DiffuseBsdf<N>(sample(d->reflectance, lambda));
  const PbrMaterial& material = std::get<PbrMaterial>(m.kind);
  const SurfaceInputs p = material.inputs(at);  // the texture coordinates are read here only (LastBsdf relies on it)
  const float alpha = sqr(p.roughness);
  // Local x is the direction of anisotropy (the shading frame follows it): α_x = mix(α, 1, s²).
  const TrowbridgeReitz distribution(p.anisotropy > 0 ? lerp(sqr(p.anisotropy), alpha, 1.f) : alpha, alpha);
  // A colour at the path's wavelengths, from the material's spectrum if it has one, else upsampled here.
  const auto sampled = [&]<typename Upsampled>(const std::optional<Upsampled>& constant, Rgb rgb) {
    return constant ? (*constant)(lambda) : Upsampled(rgb)(lambda);
  };
  static const ConstantSpectra none;
  const ConstantSpectra& constant = at.spectra ? *at.spectra : none;
  SampledSpectrum<N> n_front(1.f), color;  // the front medium's index; the base colour
  const bool vertex_colored = at.vertex_color[0] != 1 || at.vertex_color[1] != 1 || at.vertex_color[2] != 1;
  const RgbAlbedoSpectrum base =
      constant.base_color && !vertex_colored ? *constant.base_color : RgbAlbedoSpectrum(p.base_color);
  if (front)
    for (int i = 0; i < N; ++i) n_front[i] = ior(front->ior, lambda[i]);
  if (p.metallic < 1 || !material.metal) color = base(lambda);

  // The metal, relative to the surrounding medium.
  SampledSpectrum<N> n, k;
  if (p.metallic > 0) {
    if (material.metal) {
      n = sample(material.metal->n, lambda), k = sample(material.metal->k, lambda);
    } else {
      const MetalIndex<N> m = metal_nk_from_reflectance(color);
      n = m.n, k = m.k;
    }
    n /= n_front, k /= n_front;
  }
  const bool ms = material.energy_compensation;
  const bool layered = p.clearcoat > 0 || p.sheen_color.max() > 0;
  const bool film = p.iridescence > 0 && p.iridescence_thickness > 0;
  if (!layered && !film && p.specular_color == Rgb{1, 1, 1} && p.diffuse_transmission <= 0) {
    // The plain metallic-roughness model, compiled without the extensions' parts. The conductor,
    // the dielectric and the PbrBsdf are built where the Bsdf keeps them (see PbrBsdf).
    if (p.metallic >= 1) return Bsdf<N>(std::in_place_type<ConductorBsdf<N>>, distribution, n, k, ms);
    const float eta = ior(material.dielectric.ior, lambda[0]) / n_front[0];
    if (p.metallic <= 0 && p.transmission >= 1)
      return Bsdf<N>(std::in_place_type<DielectricBsdf<N>>, distribution, eta, color, p.thin_walled, p.transmission,
                     p.specular, ms);
    if (p.metallic <= 0 && p.transmission <= 0 && p.specular <= 0) return DiffuseBsdf<N>(color);  // no specular layer
    const auto metal = [&] {  // weight 0: never evaluated
      return ConductorBsdf<N>(distribution, n, k, ms && p.metallic > 0);
    };
    const auto dielectric = [&] {
      return DielectricBsdf<N>(distribution, eta, color, p.thin_walled, p.transmission, p.specular, ms);
    };
    return Bsdf<N>(std::in_place_type<PbrBsdf<N>>, p.metallic, metal, dielectric, p.transmission, color,
                   distribution.alpha(), eta, p.specular, ms);
  }

  // The extensions: a thin film over the metal and the dielectric, a specular colour, diffuse
  // transmission, under a clear coat and a sheen.
  std::optional<FilmLanes<N>> film_lanes;
  if (film)
    film_lanes.emplace(ThinFilm{p.iridescence, p.iridescence_thickness, material.iridescence->ior}, lambda, n_front);
  const auto metal = [&] {  // weight 0: never evaluated (nor its film's reflectance found)
    return ConductorBsdf<N, true>(distribution, n, k, ms && p.metallic > 0, film_lanes);
  };
  const float eta = ior(material.dielectric.ior, lambda[0]) / n_front[0];
  // Per-lane reflectance: the specular colour's indices, the film; and for the diffuse under
  // them, each lane's index (with a film, the one of the film's highest reflectance).
  std::optional<SpectralReflectance<N>> lanes;
  typename PbrBsdf<N, true>::Extras extras;
  if (film || p.specular_color != Rgb{1, 1, 1}) {
    lanes.emplace();
    lanes->film = film_lanes;
    SampledSpectrum<N> reflecting(eta);
    if (p.specular_color != Rgb{1, 1, 1}) {
      reflecting = ior_with_scaled_f0(eta, sampled(constant.specular_color, p.specular_color));
      lanes->eta = reflecting;
    }
    if ((1 - p.metallic) * (1 - p.transmission) > 0) {  // only a diffuse base of some weight is coupled
      extras.lane_etas = reflecting;
      if (film) {  // coupled as an interface of the film's peak reflectance, and its excess (thin_film.h)
        extras.lane_excess = film_reflectance_excess(film_lanes->ior, reflecting) * p.iridescence;
        for (int i = 0; i < N; ++i) (*extras.lane_etas)[i] = film_coupling_index(film_lanes->ior[i], reflecting[i]);
      }
    }
  }
  // A film's interface stays single-scattering (see dielectric_bsdf.h), and so does its E below.
  const bool dielectric_ms = ms && !film;
  const auto dielectric = [&] {
    return DielectricBsdf<N, true>(distribution, eta, color, p.thin_walled, p.transmission, p.specular, dielectric_ms,
                                   lanes);
  };
  if (p.diffuse_transmission > 0) {
    extras.diffuse_transmission = p.diffuse_transmission;
    extras.transmitted_albedo = sampled(constant.diffuse_transmission_color, p.diffuse_transmission_color);
  }
  std::optional<typename LayeredBsdf<N>::Coat> coat;
  if (p.clearcoat > 0) coat = {p.clearcoat, sqr(p.clearcoat_roughness), 1.5f / n_front[0], at.coat_normal, ms};
  std::optional<typename LayeredBsdf<N>::Sheen> sheen;
  if (p.sheen_color.max() > 0) sheen = {sampled(constant.sheen_color, p.sheen_color), sqr(p.sheen_roughness)};
  // Built where it is kept, the base and its lobes inside it (not copied there).
  return Bsdf<N>(std::in_place_type<LayeredBsdf<N>>, coat, sheen, p.metallic, metal, dielectric, p.transmission, color,
                 distribution.alpha(), eta, p.specular, dielectric_ms, &extras);
}

// make_bsdf for integrators that follow only the hero wavelength past a λ-dependent index ratio:
// it terminates lambda's secondary wavelengths there first (pbrt-v4 §10.5.1).
template <int N>
Bsdf<N> make_hero_bsdf(const Material& m, const SurfacePoint& at, SampledWavelengths<N>& lambda,
                       const Dielectric* front) {
  if (disperses(m, front)) lambda.terminate_secondary();
  return make_bsdf(m, at, lambda, front);
}

}  // namespace prism
