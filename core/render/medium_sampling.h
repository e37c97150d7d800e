#pragma once
// Crossing a homogeneous medium (materials/medium.h) with all of a path's wavelengths at once.
//
// Transmittance over a distance d is T(λ) = exp(−σ_t(λ) d), exact (Beer–Lambert): it is all an
// absorbing medium does to a path, and all a shadow ray needs. A scattering medium is crossed by
// sampling where light scatters next. Its σ_t varies with λ, so one distance serves every lane
// only through hero-wavelength spectral MIS (Wilkie et al. 2014), as at dispersive interfaces
// (materials/dispersive_bsdf.h, whose header derives it): the hero (lane 0) samples t from its own
// density, p_0(t) = σ_t,0 e^{−σ_t,0 t} for an event before the surface at t_max or
// P_0 = e^{−σ_t,0 t_max} for none; each lane k takes f_k = σ_s,k e^{−σ_t,k t} (or e^{−σ_t,k t_max})
// over p̄ = Σ_j q_j p_j / Σ_j q_j, the lanes' densities of the same event weighted by the path's
// pdfs under each lane so far (q_j, `path_pdfs`), which the event then multiplies by p_j. That is
// the balance heuristic over the lanes as heroes: unbiased for every lane however σ_t differs
// across them — also where the hero's σ_t is 0 and it could never scatter — with the variance of
// the best lane's density, where weighing by the hero's density alone diverges for lanes whose σ_t
// is many times the hero's. (A majorant over the lanes, pbrt-v4's null-scattering formulation,
// would add null events a homogeneous medium does not need: each lane's density is an exact
// exponential.)

#include <cmath>

#include "materials/medium.h"
#include "spectral/sampled_spectrum.h"

namespace prism {

// A medium's coefficients at a path's wavelengths, sampled once while the path stays in it.
template <int N>
class MediumCoefficients {
 public:
  // Those of m (kept from the last call while m is the same medium).
  const MediumCoefficients& of(const Medium& m, const SampledWavelengths<N>& lambda) {
    if (&m == medium_) return *this;
    medium_ = &m;
    sigma_s = m.sigma_s ? sample(*m.sigma_s, lambda) : SampledSpectrum<N>(0.f);
    sigma_t = sigma_s + (m.sigma_a ? sample(*m.sigma_a, lambda) : SampledSpectrum<N>(0.f));
    return *this;
  }

  // T(λ) = e^{−σ_t d}; an infinite distance gives 0 where σ_t > 0 and 1 where it is 0 (never NaN).
  SampledSpectrum<N> transmittance(float d) const {
    SampledSpectrum<N> t;
    for (int i = 0; i < N; ++i) t[i] = sigma_t[i] > 0 ? std::exp(-sigma_t[i] * d) : 1.f;
    return t;
  }

  SampledSpectrum<N> sigma_s, sigma_t;

 private:
  const Medium* medium_ = nullptr;
};

// T(λ) over a distance d of medium m (1 for none), its coefficients sampled for this segment alone.
template <int N>
SampledSpectrum<N> transmittance(const Medium* m, float d, const SampledWavelengths<N>& lambda) {
  if (!m) return SampledSpectrum<N>(1.f);
  return MediumCoefficients<N>().of(*m, lambda).transmittance(d);
}

// Where a path crossing a scattering medium towards a surface at t_max (∞: none) scatters.
template <int N>
struct MediumEvent {
  bool scattered;  // at t; else it reaches t_max
  float t;
  SampledSpectrum<N> weight;  // f_k / p̄ (see the header): what the path's throughput takes
  float pdf;                  // p̄ of passing (when not scattered), for the MIS of light met at t_max
};

// The event from u ∈ [0, 1), updating path_pdfs (the q_j), kept from underflowing by their maximum.
template <int N>
MediumEvent<N> sample_medium_event(const MediumCoefficients<N>& c, float t_max, float u,
                                   SampledSpectrum<N>& path_pdfs) {
  const float sigma_hero = c.sigma_t[0];
  const float t = sigma_hero > 0 ? -std::log1p(-u) / sigma_hero : kInfinity;
  const bool scattered = t < t_max;
  const SampledSpectrum<N> T = c.transmittance(scattered ? t : t_max);
  const SampledSpectrum<N> pdf = scattered ? c.sigma_t * T : T;
  const SampledSpectrum<N> f = scattered ? c.sigma_s * T : T;
  const float mean = (path_pdfs * pdf).average() / path_pdfs.average();
  path_pdfs *= pdf;
  if (const float m = path_pdfs.max(); m > 0) path_pdfs /= m;
  if (!(mean > 0)) return {scattered, scattered ? t : t_max, SampledSpectrum<N>(0.f), 0.f};
  return {scattered, scattered ? t : t_max, f / mean, mean};
}

// The mean transmittance of a segment weighted by the path's pdfs under each lane, Σ q_j T_j / Σ q_j:
// the probability that BSDF or phase sampling, followed by the lanes' distance sampling, passes it
// (the factor its pdf takes in MIS against light sampling across a scattering medium).
template <int N>
float mean_transmittance(const SampledSpectrum<N>& T, const SampledSpectrum<N>& path_pdfs) {
  return (path_pdfs * T).average() / path_pdfs.average();
}

}  // namespace prism
