#pragma once
// Conductor: microfacet reflection (Cook & Torrance 1982 with GGX; Walter et al. 2007)
//   f(wo, wi) = D(m) F(wo·m) G(wo, wi) / (4 |cos θ_o cos θ_i|),  m = normalize(wo + wi),
// with the exact complex Fresnel reflectance of n(λ) + ik(λ) per lane; a mirror when smooth.
// Multiple scattering between the microfacets, which the single-scattering f loses (up to 59% of
// the light of a white metal at roughness 1), is added back with the lobe's own shape (Turquin
// 2019, "Practical multiple scattering compensation for microfacet models"):
//   f_ms = (1 + F0 (1 − E(μ_o)) / E(μ_o)) f,   E the white lobe's directional albedo (SpecularAlbedo),
// so that a lossless surface (F = 1) reflects everything; it samples again where a visible normal
// sends wo below the surface (sample_tries.h). Off (`compensate` false) it is the single-scattering
// lobe of Cycles 3.x and most real-time renderers, sampled once.
// Two-sided: a direction below the surface sees the same lobe, mirrored. An optional thin film
// (KHR_materials_iridescence) over the metal replaces F (and F0) by the film's exact reflectance
// (compiled in with Extensions = true).

#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "materials/sample_tries.h"
#include "materials/specular_albedo.h"
#include "materials/thin_film.h"

namespace prism {

template <int N, bool Extensions = false>
class ConductorBsdf {
 public:
  // n, k: the metal's complex index relative to the surrounding medium, per lane.
  ConductorBsdf(const TrowbridgeReitz& distribution, const SampledSpectrum<N>& n, const SampledSpectrum<N>& k,
                bool compensate = true, const OptionalPart<Extensions, FilmLanes<N>>& film = {})
      : distribution_(distribution),
        smooth_(distribution.effectively_smooth()),
        compensate_(compensate && !smooth_),
        roughness_(compensate_ ? SpecularAlbedo::roughness(distribution.alpha()) : SpecularAlbedo::Roughness{}),
        n_(n),
        k_(k),
        film_(film) {
    if constexpr (Extensions)
      if (film_ && compensate_) film_f0_ = reflectance(1.f);
  }

  bool is_specular() const { return smooth_; }

  SampledSpectrum<N> reflectance(float cos_theta) const {
    if constexpr (Extensions)
      if (film_)
        return film_->reflectance(std::abs(cos_theta), [&](int i) { return std::complex<float>(n_[i], k_[i]); });
    // All lanes at once, as vector code (fresnel_conductor has no branches).
    SampledSpectrum<N> r;
    for (int i = 0; i < N; ++i) r[i] = fresnel_conductor(cos_theta, n_[i], k_[i]);
    return r;
  }

  DeltaLobes<N> delta_lobes(const Vec3f& wo) const {
    DeltaLobes<N> d;
    if (smooth_ && wo.z != 0) d.add({Vec3f(-wo.x, -wo.y, wo.z), reflectance(wo.z), false, 1.f});
    return d;
  }

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const { return eval(wo, wi).f; }

  // f and pdf with one half vector m, one D(m) and one Λ(wo).
  BsdfEval<N> eval(Vec3f wo, Vec3f wi) const {
    const auto wm = half_vector(wo, wi);
    if (!wm) return {SampledSpectrum<N>(0.f), 0.f};
    const TrowbridgeReitz::Facet t = distribution_.facet(wo, wi, *wm);
    const SampledSpectrum<N> f = reflectance(dot(wo, *wm)) * (t.D * t.G / (4 * wo.z * wi.z));
    if (!compensate_) return {f, TrowbridgeReitz::reflected_pdf(wo, t)};
    return {f * multiple_scattering(wo.z), TrowbridgeReitz::reflected_pdf(wo, t) * tries(wo.z).pdf_scale};
  }

  // Visible-normal sampling: pdf(wi) = D_wo(m) / (4 |wo·m|) = G1(wo) D(m) / (4 |cos θ_o|), over
  // the tries when compensated.
  float pdf(Vec3f wo, Vec3f wi) const {
    const auto wm = half_vector(wo, wi);
    if (!wm) return 0.f;
    return distribution_.reflected_pdf(wo, *wm) * tries(wo.z).pdf_scale;
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f u) const {
    if (wo.z == 0) return std::nullopt;
    if (smooth_) {
      const Vec3f wi(-wo.x, -wo.y, wo.z);
      return BsdfSample<N>{reflectance(wo.z) / abs_cos_theta(wi), wi, 1.f, true, false, 1.f};
    }
    const float sign = wo.z < 0 ? -1.f : 1.f;
    const int count = tries(wo.z).count;
    for (int k = 1;; ++k) {
      const Vec3f wm = distribution_.sample_visible_normal(wo * sign, u) * sign;
      if (const Vec3f wi = reflect(wo, wm); same_hemisphere(wo, wi)) {
        const BsdfEval<N> e = eval(wo, wi);
        if (!(e.pdf > 0)) return std::nullopt;
        return BsdfSample<N>{e.f, wi, e.pdf, false, false, 1.f};
      }
      if (k >= count) return std::nullopt;
      sample_tries::next(uc, u);
    }
  }

 private:
  // How many tries a sample takes (sample_tries.h): those of a lossless reflection when compensated.
  sample_tries::Tries tries(float mu) const {
    if (!compensate_ || !distribution_.isotropic()) return sample_tries::kOneTry;
    return sample_tries::tries(SpecularAlbedo::table().white_valid(std::abs(mu), roughness_));
  }

  // The reflection's half vector m = normalize(wo + wi), with wo and wi turned to the upper
  // hemisphere; none for a smooth lobe, directions on opposite sides, or wo = −wi.
  std::optional<Vec3f> half_vector(Vec3f& wo, Vec3f& wi) const {
    if (smooth_ || !same_hemisphere(wo, wi)) return std::nullopt;
    if (wo.z < 0) wo = -wo, wi = -wi;
    const Vec3f m = wo + wi;
    if (length_squared(m) == 0) return std::nullopt;
    return normalize(m);
  }

  // 1 + F0 (1 − E(μ)) / E(μ), F0 = ((n − 1)² + k²) / ((n + 1)² + k²) the normal reflectance.
  SampledSpectrum<N> multiple_scattering(float mu) const {
    const float e = SpecularAlbedo::table().white(mu, roughness_);
    SampledSpectrum<N> r;
    for (int i = 0; i < N; ++i) {
      const float k2 = k_[i] * k_[i];
      const float f0 = n_[i] == 0 && k_[i] == 0 ? 1.f : (sqr(n_[i] - 1) + k2) / (sqr(n_[i] + 1) + k2);
      const float f0_film = [&] {
        if constexpr (Extensions)
          if (film_f0_) return (*film_f0_)[i];
        return f0;
      }();
      r[i] = 1 + f0_film * (1 - e) / e;
    }
    return r;
  }

  TrowbridgeReitz distribution_;
  bool smooth_, compensate_;
  SpecularAlbedo::Roughness roughness_;  // where α falls on the albedo tables, when compensating
  SampledSpectrum<N> n_, k_;
  [[no_unique_address]] OptionalPart<Extensions, FilmLanes<N>> film_;
  [[no_unique_address]] OptionalPart<Extensions, SampledSpectrum<N>>
      film_f0_;  // the film's reflectance at normal incidence
};

}  // namespace prism
