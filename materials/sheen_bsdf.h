#pragma once
// Sheen: the "Charlie" distribution of fibres standing on the surface (Estevez & Kulla 2017,
// "Production Friendly Microfacet Sheen BRDF"), as KHR_materials_sheen specifies it:
//   f = C · D(m) G(wo, wi) / (4 |cos θ_o cos θ_i|),  m = normalize(wo + wi),
//   D(m) = (2 + 1/α) sin^{1/α} θ_m / (2π),  G = 1 / (1 + Λ(μ_o) + Λ(μ_i)),
// α = sheenRoughness², Λ their fitted shadowing (exp of L(μ) = a/(1 + b μ^c) + d μ + e, mirrored
// about μ = ½ for the terminator). Sampled with the cosine-weighted hemisphere: pdf = |cos θ_i|/π
// (the lobe is broad and faint; the mixture that holds it samples the sharp lobes).
// Two-sided: a direction below the surface sees the same lobe, mirrored. Where the fitted lobe
// would reflect more than it receives (grazing, α < 0.1), it is scaled down to an albedo of
// at most 1 (SheenAlbedo::scale).

#include <cmath>
#include <optional>

#include "core/base/per_thread_cache.h"
#include "core/base/warp.h"
#include "materials/bsdf_sample.h"
#include "materials/sheen_albedo.h"

namespace prism {

class CharlieSheen {
 public:
  explicit CharlieSheen(float alpha)
      : alpha_(std::clamp(alpha, 1e-3f, 1.f)),
        fit_(sqr(1 - alpha_)),
        L_half_(L(0.5f)),
        D_scale_((2 + 1 / alpha_) / (2 * kPi)),
        D_power_(0.5f / alpha_) {}

  // D of a normal m with cos²θ_m = cos2: (sin²θ_m)^{1/(2α)} scaled.
  float D(float cos2) const { return D_scale_ * std::pow(std::max(0.f, 1 - cos2), D_power_); }
  // The height-correlated G(wo, wi), with Λ(μ_o) given (found once per wo).
  float G(float lambda_o, const Vec3f& wi) const { return 1 / (1 + lambda_o + Lambda(std::abs(wi.z))); }
  // f / C for directions on the same side.
  float value(const Vec3f& wo, const Vec3f& wi) const { return value(wo, wi, Lambda(std::abs(wo.z))); }
  float value(const Vec3f& wo, const Vec3f& wi, float lambda_o) const {
    const Vec3f m = wo + wi;  // the half vector, unnormalised: D needs only its cos²θ
    const float m2 = length_squared(m);
    if (wo.z == 0 || wi.z == 0 || m2 == 0) return 0.f;
    return D(m.z * m.z / m2) * G(lambda_o, wi) / std::abs(4 * wo.z * wi.z);
  }
  float Lambda(float mu) const { return mu < 0.5f ? std::exp(L(mu)) : std::exp(2 * L_half_ - L(1 - mu)); }

 private:
  // Estevez & Kulla's fit, its five parameters blended between α = 0 and α = 1 by (1 − α)².
  struct Fit {
    float a, b, c, d, e;
    explicit Fit(float t)
        : a(lerp(t, 21.5473f, 25.3245f)),
          b(lerp(t, 3.82987f, 3.32435f)),
          c(lerp(t, 0.19823f, 0.16801f)),
          d(lerp(t, -1.97760f, -1.27393f)),
          e(lerp(t, -4.32054f, -4.85967f)) {}
  };
  float L(float mu) const { return fit_.a / (1 + fit_.b * std::pow(mu, fit_.c)) + fit_.d * mu + fit_.e; }

  float alpha_;
  Fit fit_;                  // the fit's parameters at α_
  float L_half_;             // L(½), where Λ is mirrored
  float D_scale_, D_power_;  // (2 + 1/α) / (2π) and 1/(2α)
};

// What a sheen of roughness α needs that depends on α alone: the fitted lobe (its parameters, and
// L(½), a pow), its albedo's scale and its albedo along μ. A material's few α recur at every hit,
// so the last few are kept per thread.
struct SheenRoughness {
  CharlieSheen charlie;
  float scale;
  SheenAlbedo::Curve albedo;

  static SheenRoughness of(float alpha) {
    return per_thread_cached(alpha, [](float a) {
      return SheenRoughness{CharlieSheen(a), SheenAlbedo::scale(a), SheenAlbedo::curve(a)};
    });
  }
};

template <int N>
class SheenBsdf {
 public:
  SheenBsdf(const SampledSpectrum<N>& color, const SheenRoughness& roughness)
      : color_(color * roughness.scale), charlie_(roughness.charlie) {}

  bool is_specular() const { return false; }
  DeltaLobes<N> delta_lobes(const Vec3f&) const { return {}; }

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const {
    return same_hemisphere(wo, wi) ? color_ * charlie_.value(wo, wi, lambda_o(wo)) : SampledSpectrum<N>(0.f);
  }

  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(abs_cos_theta(wi)) : 0.f;
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float, Vec2f u) const {
    Vec3f wi = sample_cosine_hemisphere(u);
    if (wo.z < 0) wi.z = -wi.z;
    const float p = pdf(wo, wi);
    if (!(p > 0)) return std::nullopt;
    return BsdfSample<N>{f(wo, wi), wi, p};
  }

 private:
  // Λ(μ_o), kept for the next evaluation from the same wo (a path evaluates the BSDF of one hit
  // from one wo: towards its light samples and its BSDF sample).
  float lambda_o(const Vec3f& wo) const {
    const float mu = std::abs(wo.z);
    if (mu != outgoing_.mu) outgoing_ = {mu, charlie_.Lambda(mu)};
    return outgoing_.lambda;
  }

  SampledSpectrum<N> color_;
  CharlieSheen charlie_;
  struct Outgoing {
    float mu = -1;  // none yet
    float lambda;
  };
  mutable Outgoing outgoing_;  // a cache: safe because a Bsdf is built and used within one thread
};

}  // namespace prism
