#pragma once
// Materials as the scene describes them (wavelength-independent), and the BSDF a material
// yields at one hit for one path's wavelengths.

#include <optional>
#include <string>
#include <variant>

#include "materials/bsdf.h"
#include "materials/ior.h"
#include "spectral/spectrum.h"

namespace prism {

struct DiffuseMaterial {
  Spectrum reflectance = ConstantSpectrum{0.8f};
};

// A metal: complex index n(λ) + ik(λ), measured (catalogue) or derived from a colour.
struct ConductorMaterial {
  Spectrum n, k;
  std::string catalogue;  // the catalogue key of a measured metal; empty when made from a colour
};

// The metal of a colour (glTF's baseColor of a metallic material): at each nm, the n, k of
// Gulbrandsen's parametrisation whose normal-incidence reflectance is the colour's value and
// whose edge tint makes the directional albedo equal to that of glTF's reference metal
// (Schlick with F0 = colour). Measured metals in the visible sit close to it (edge tints
// 0.9-1 for Cu, Al, Ag, Au); the Fresnel formula itself stays exact.
ConductorMaterial conductor_from_reflectance(const Spectrum& reflectance);

// A dielectric interface. Closed volumes (not thin-walled) are entered and left by paths; the
// interior absorbs by Beer–Lambert with absorption coefficient σ_a(λ) per scene unit.
struct DielectricMaterial {
  DielectricMaterial(IorModel ior_model, Spectrum tint = ConstantSpectrum{1}, std::optional<Spectrum> sigma_a = {},
                     bool thin = false)
      : ior(std::move(ior_model)), transmission_tint(std::move(tint)), absorption(std::move(sigma_a)),
        thin_walled(thin), dispersive(is_dispersive(ior)) {}

  IorModel ior;
  Spectrum transmission_tint;
  std::optional<Spectrum> absorption;
  bool thin_walled;
  bool dispersive;  // derived from ior
};

using MaterialKind = std::variant<DiffuseMaterial, ConductorMaterial, DielectricMaterial>;

struct Material {
  std::string name;
  MaterialKind kind;
  std::optional<Spectrum> emission;  // emitted radiance; front face only unless double_sided
  bool double_sided = false;

  const DielectricMaterial* dielectric() const { return std::get_if<DielectricMaterial>(&kind); }
};

// The BSDF of material m for the path's wavelengths. For a dielectric, `front` is the
// dielectric on the front (normal) side of the surface, or nullptr for vacuum. A λ-dependent
// index ratio terminates the path's secondary wavelengths (pbrt-v4 §10.5.1).
template <int N>
Bsdf<N> make_bsdf(const Material& m, SampledWavelengths<N>& lambda, const DielectricMaterial* front) {
  if (const auto* d = std::get_if<DiffuseMaterial>(&m.kind)) return DiffuseBsdf<N>(sample(d->reflectance, lambda));
  if (const auto* c = std::get_if<ConductorMaterial>(&m.kind)) {
    SampledSpectrum<N> n = sample(c->n, lambda), k = sample(c->k, lambda);
    if (front) {  // relative to the surrounding dielectric
      for (int i = 0; i < N; ++i) {
        const float n_out = ior(front->ior, lambda[i]);
        n[i] /= n_out;
        k[i] /= n_out;
      }
    }
    return ConductorBsdf<N>(n, k);
  }
  const auto& d = std::get<DielectricMaterial>(m.kind);
  if (d.dispersive || (front && front->dispersive)) lambda.terminate_secondary();
  const float eta = ior(d.ior, lambda[0]) / (front ? ior(front->ior, lambda[0]) : 1.f);
  return DielectricBsdf<N>(eta, sample(d.transmission_tint, lambda), d.thin_walled);
}

}  // namespace prism
