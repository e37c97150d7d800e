#pragma once
// The BSDF a material yields at one surface point for one path's wavelengths: the factory of the
// closed set in bsdf.h, from the material description of material.h.

#include <optional>

#include "materials/bsdf.h"
#include "materials/material.h"
#include "materials/metal_fit.h"

namespace prism {

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
  const SurfaceInputs p = material.inputs(at);  // the texture coordinates are read here only (BsdfCache relies on it)
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
  if (p.metallic < 1 || !material.metal) color = material.base_spectrum(p.base_color, base, lambda);

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
