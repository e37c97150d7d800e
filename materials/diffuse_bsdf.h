#pragma once
// Lambertian reflection: f = R / π on the side of wo, sampled with the cosine-weighted
// hemisphere so that f·cos/pdf = R exactly.

#include <optional>

#include "core/base/warp.h"
#include "materials/bsdf_sample.h"

namespace prism {

template <int N>
class DiffuseBsdf {
 public:
  explicit DiffuseBsdf(const SampledSpectrum<N>& reflectance) : r_(reflectance) {}

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const {
    return same_hemisphere(wo, wi) ? r_ * kInvPi : SampledSpectrum<N>(0.f);
  }

  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0.f;
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float /*uc*/, Vec2f u) const {
    Vec3f wi = sample_cosine_hemisphere(u);
    if (wo.z < 0) wi.z = -wi.z;
    const float pdf = cosine_hemisphere_pdf(abs_cos_theta(wi));
    if (pdf == 0.f) return std::nullopt;
    return BsdfSample<N>{r_ * kInvPi, wi, pdf};
  }

  bool is_specular() const { return false; }
  DeltaLobes<N> delta_lobes(const Vec3f&) const { return {}; }

 private:
  SampledSpectrum<N> r_;
};

}  // namespace prism
