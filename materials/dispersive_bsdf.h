#pragma once
// DispersiveBsdf<N>: a material whose index ratio varies with λ, for all of a path's wavelengths
// at once, by hero-wavelength spectral MIS (Wilkie et al. 2014, "Hero Wavelength Spectral
// Sampling", EGSR: the balance heuristic over the wavelengths as heroes). Each lane is the
// material's BSDF at its own wavelength, so at its own index: the hero (lane 0) samples the
// direction, every lane evaluates f and pdf with its own index.
//
// The path's wavelengths are the CDF values (s + k)/N of one uniform s, and the hero is one of
// them chosen uniformly (wavelengths.h); so "lane j had been the hero" is a sampling technique of
// the same (s, path) space, picked with probability 1/N, whose path pdf p_j is the product of its
// vertices' pdfs at λ_j. (In s the wavelength pdfs p(λ_j) cancel against dλ_j/ds = 1/(N p(λ_j)):
// unlike the paper's equal spacing in λ, they do not enter the weights.) One-sample MIS with the
// balance heuristic (Veach 1997, §9.2.4, the one-sample model) gives every lane k the estimate
//   f_k(x) / ((1/N) Σ_j p_j(x))
// i.e. the throughput divided, at each vertex, by the lanes' pdfs of its direction averaged with
// the weights q_j = the path's pdf under lane j so far:  p̄ = Σ_j q_j p_j(ω) / Σ_j q_j; the
// product of the p̄ telescopes to (1/N) Σ_j p_j. `pdf` in eval and sample_f is that p̄, and MIS
// against light sampling uses it too (the balance heuristic on p̄ and the light's λ-independent pdf):
// the weights of the 2N techniques, N heroes × {BSDF, light}, then sum to 1 on every path.
// A delta sample of the hero (a smooth refraction, but also a smooth reflection or a smooth coat's
// lobe) is given pdf 0 and f 0 under every other lane: the path goes on with the hero alone,
// N-fold (the q_j of the others become 0), which is the termination of the secondary wavelengths
// (pbrt-v4 §4.5.4) as a special case. (A delta direction all lanes share, such as a mirror
// reflection, could keep them with each lane's own probability of choosing that lobe; not done.)

#include <array>
#include <optional>

#include "materials/make_bsdf.h"

namespace prism {

template <int N>
class DispersiveBsdf {
 public:
  // The lanes' BSDFs of material m at `at` for the wavelengths `lambda`; path_pdfs are the q_j
  // above (all 1 at the camera), which sample_f multiplies by the lanes' pdfs of its direction.
  // A specular BSDF only ever gives its hero's delta samples: its other lanes are not built.
  DispersiveBsdf(const Material& m, const SurfacePoint& at, const SampledWavelengths<N>& lambda,
                 const Dielectric* front, SampledSpectrum<N>& path_pdfs)
      : path_pdfs_(path_pdfs) {
    const auto lane_bsdf = [&](int i) { return make_bsdf(m, at, lambda.lane(i), front); };
    lanes_[0] = lane_bsdf(0);
    if (!is_specular())
      for (int i = 1; i < N; ++i) lanes_[i] = lane_bsdf(i);
  }

  bool is_specular() const { return bsdf_is_specular(*lanes_[0]); }

  // f of every lane at its own index, and p̄ (see the header).
  BsdfEval<N> eval(const Vec3f& wo, const Vec3f& wi) const {
    if (is_specular()) return {SampledSpectrum<N>(0.f), 0.f};
    SampledSpectrum<N> f, pdf;
    for (int i = 0; i < N; ++i) {
      const BsdfEval<1> e = bsdf_eval(*lanes_[i], wo, wi);
      f[i] = e.f[0], pdf[i] = e.pdf;
    }
    return {f, mean_pdf(pdf)};
  }

  // The hero's sample, with every lane's f and p̄ as its pdf; multiplies path_pdfs by the lanes'
  // pdfs of the sampled direction (0 for the others after a delta sample).
  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f u) const {
    const auto hero = bsdf_sample_f(*lanes_[0], wo, uc, u);
    if (!hero || !(hero->pdf > 0)) return std::nullopt;
    SampledSpectrum<N> f(0.f), pdf(0.f);
    f[0] = hero->f[0], pdf[0] = hero->pdf;
    if (!hero->specular)
      for (int i = 1; i < N; ++i) {
        const BsdfEval<1> e = bsdf_eval(*lanes_[i], wo, hero->wi);
        f[i] = e.f[0], pdf[i] = e.pdf;
      }
    const float p = mean_pdf(pdf);
    path_pdfs_ *= pdf;
    if (const float m = path_pdfs_.max(); m > 0) path_pdfs_ /= m;  // only their ratios count: kept from underflowing
    return BsdfSample<N>{f, hero->wi, p, hero->specular, hero->transmission, hero->eta};
  }

 private:
  float mean_pdf(const SampledSpectrum<N>& pdf) const { return (path_pdfs_ * pdf).average() / path_pdfs_.average(); }

  std::array<std::optional<Bsdf<1>>, N> lanes_;
  SampledSpectrum<N>& path_pdfs_;
};

// The calls the integrators make on a Bsdf<N> (bsdf.h), for a dispersive one.
template <int N>
bool bsdf_is_specular(const DispersiveBsdf<N>& b) {
  return b.is_specular();
}
template <int N>
BsdfEval<N> bsdf_eval(const DispersiveBsdf<N>& b, const Vec3f& wo, const Vec3f& wi) {
  return b.eval(wo, wi);
}
template <int N>
std::optional<BsdfSample<N>> bsdf_sample_f(const DispersiveBsdf<N>& b, const Vec3f& wo, float uc, Vec2f u) {
  return b.sample_f(wo, uc, u);
}

// Whether any lane but the hero can still follow a path whose pdfs under the lanes are path_pdfs
// (after a delta refraction at a dispersive interface, none can).
template <int N>
bool companions_alive(const SampledSpectrum<N>& path_pdfs) {
  for (int i = 1; i < N; ++i)
    if (path_pdfs[i] > 0) return true;
  return false;
}

}  // namespace prism
