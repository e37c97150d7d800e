#pragma once
// Smooth dielectric interface: specular reflection with probability R (exact Fresnel, total
// internal reflection included) and transmission with probability T = 1 − R, so that
// f·|cos|/pdf is exactly 1 for reflection and tint·T'/T for transmission.
//   closed surface: Snell refraction; radiance is scaled by 1/η² across the interface
//                   (Veach 1997, §5.2), so T' = T/η²;
//   thin wall:      a sheet with no interior: light passes straight through and the two
//                   interfaces' inter-reflections sum to R' = R + T²R/(1 − R²), T' = 1 − R'
//                   (pbrt-v4 §9.5.1).

#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace prism {

template <int N>
struct Transmission {
  Vec3f wi;
  SampledSpectrum<N> weight;  // the transmitted share: tint · T, divided by η² when refracted
  float eta;                  // relative index crossed (1 for a thin wall)
};

template <int N>
class DielectricBsdf {
 public:
  // eta = n_back / n_front (the index behind the shading normal over the one in front), one
  // value for all lanes: a λ-dependent index terminates the secondary wavelengths first.
  // tint multiplies transmitted light (glTF's base colour on transmission; 1 for clear glass).
  DielectricBsdf(float eta, const SampledSpectrum<N>& tint, bool thin) : eta_(eta), tint_(tint), thin_(thin) {}

  SampledSpectrum<N> f(const Vec3f&, const Vec3f&) const { return SampledSpectrum<N>(0.f); }
  float pdf(const Vec3f&, const Vec3f&) const { return 0.f; }
  bool is_specular() const { return true; }

  // Fraction of light reflected towards wo.
  float reflectance(const Vec3f& wo) const {
    if (!thin_) return fresnel_dielectric(cos_theta(wo), eta_);
    const float R = fresnel_dielectric(abs_cos_theta(wo), eta_);
    return R < 1 ? R + sqr(1 - R) * R / (1 - R * R) : R;
  }

  // The transmitted direction and share, or nothing under total internal reflection.
  std::optional<Transmission<N>> transmission(const Vec3f& wo) const {
    const float T = 1 - reflectance(wo);
    if (T <= 0) return std::nullopt;
    if (thin_) return Transmission<N>{-wo, tint_ * T, 1.f};
    const auto refraction = refract(wo, {0, 0, 1}, eta_);
    if (!refraction) return std::nullopt;
    return Transmission<N>{refraction->wt, tint_ * (T / sqr(refraction->eta_p)), refraction->eta_p};
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f) const {
    const float R = reflectance(wo);
    if (uc < R) {
      const Vec3f wi(-wo.x, -wo.y, wo.z);
      return BsdfSample<N>{SampledSpectrum<N>(R / abs_cos_theta(wi)), wi, R, true, false, 1.f};
    }
    const auto t = transmission(wo);
    if (!t) return std::nullopt;
    const float T = 1 - R;
    return BsdfSample<N>{t->weight / abs_cos_theta(t->wi), t->wi, T, true, true, t->eta};
  }

 private:
  float eta_;
  SampledSpectrum<N> tint_;
  bool thin_;
};

}  // namespace prism
