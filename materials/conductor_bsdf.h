#pragma once
// Smooth conductor: mirror reflection weighted by the exact complex Fresnel reflectance of
// n(λ) + ik(λ) at each of the path's wavelengths.

#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace prism {

template <int N>
class ConductorBsdf {
 public:
  // n, k: the metal's complex index relative to the surrounding medium, per lane.
  ConductorBsdf(const SampledSpectrum<N>& n, const SampledSpectrum<N>& k) : n_(n), k_(k) {}

  SampledSpectrum<N> f(const Vec3f&, const Vec3f&) const { return SampledSpectrum<N>(0.f); }
  float pdf(const Vec3f&, const Vec3f&) const { return 0.f; }
  bool is_specular() const { return true; }

  SampledSpectrum<N> reflectance(float cos_theta) const {
    SampledSpectrum<N> r;
    for (int i = 0; i < N; ++i) r[i] = fresnel_conductor(cos_theta, n_[i], k_[i]);
    return r;
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float, Vec2f) const {
    if (wo.z == 0) return std::nullopt;
    const Vec3f wi(-wo.x, -wo.y, wo.z);
    return BsdfSample<N>{reflectance(wo.z) / abs_cos_theta(wi), wi, 1.f, true, false, 1.f};
  }

 private:
  SampledSpectrum<N> n_, k_;
};

}  // namespace prism
