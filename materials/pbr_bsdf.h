#pragma once
// glTF's metallic-roughness model, physically (glTF 2.0 Appendix B; KHR_materials_transmission):
//   f = m · f_metal + (1 − m) · [ f_dielectric + (1 − t) · f_diffuse ]
// m = metallic, t = transmission; f_metal a conductor, f_dielectric the dielectric interface
// (its reflection, and its transmission weighted by t), f_diffuse the Lambertian base under the
// specular layer, coupled to it so that the whole stays energy-consistent and reciprocal:
//   f_diffuse = ρ/π · (1 − E(μ_o)) (1 − E(μ_i)) / (1 − E_avg)      (see SpecularAlbedo)
// Sampled by choosing a lobe with probability ∝ its albedo seen from wo, then sampling it; f and
// pdf of non-delta directions are those of the whole mixture (for MIS). Without transmission
// the surface is opaque and two-sided: seen from behind, it is the same as from the front.

#include <array>
#include <optional>

#include "base/warp.h"
#include "materials/conductor_bsdf.h"
#include "materials/dielectric_bsdf.h"
#include "materials/specular_albedo.h"

namespace prism {

template <int N>
class PbrBsdf {
 public:
  // alpha, eta, specular and compensated must be those of `dielectric` (they pick its albedo E).
  PbrBsdf(float metallic, const ConductorBsdf<N>& metal, const DielectricBsdf<N>& dielectric, float transmission,
          const SampledSpectrum<N>& albedo, float alpha, float eta, float specular, bool compensated)
      : metallic_(metallic),
        transmission_(transmission),
        metal_(metal),
        dielectric_(dielectric),
        albedo_(albedo),
        alpha_(alpha),
        eta_(eta),
        specular_(specular),
        compensated_(compensated),
        e_avg_(specular * SpecularAlbedo::table().average(alpha, eta, compensated)) {}

  bool is_specular() const {
    return (metallic_ == 0 || metal_.is_specular()) && dielectric_.is_specular() && diffuse_weight() == 0;
  }

  DeltaLobes<N> delta_lobes(const Vec3f& wo) const {
    if (flips(wo)) return mirrored(delta_lobes(-wo));
    DeltaLobes<N> d;
    if (metallic_ > 0) d.add_scaled(metal_.delta_lobes(wo), metallic_);
    d.add_scaled(dielectric_.delta_lobes(wo), 1 - metallic_);
    return d;
  }

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const {
    if (flips(wo)) return f(-wo, -wi);
    SampledSpectrum<N> r = metal_.f(wo, wi) * metallic_ + dielectric_.f(wo, wi) * (1 - metallic_);
    if (diffuse_weight() > 0 && same_hemisphere(wo, wi)) r += albedo_ * (diffuse_weight() * coupling(wo, wi) * kInvPi);
    return r;
  }

  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    if (flips(wo)) return pdf(-wo, -wi);
    return mixture_pdf(wo, wi, lobe_probabilities(wo));
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f u) const {
    if (flips(wo)) {
      auto s = sample_f(-wo, uc, u);
      if (s) s->wi = -s->wi;
      return s;
    }
    const auto p = lobe_probabilities(wo);
    std::optional<BsdfSample<N>> s;
    if (uc < p[0]) {
      s = metal_.sample_f(wo, uc / p[0], u);
      if (s && s->specular) return scaled(*s, metallic_, p[0]);
    } else if (uc < p[0] + p[1]) {
      s = dielectric_.sample_f(wo, std::min((uc - p[0]) / p[1], 0.99999994f), u);
      if (s && s->specular) return scaled(*s, 1 - metallic_, p[1]);
    } else {
      Vec3f wi = sample_cosine_hemisphere(u);
      if (wo.z < 0) wi.z = -wi.z;
      s = BsdfSample<N>{{}, wi, 0.f};
    }
    if (!s) return std::nullopt;
    s->f = f(wo, s->wi);
    s->pdf = mixture_pdf(wo, s->wi, p);
    if (!(s->pdf > 0)) return std::nullopt;
    return s;
  }

 private:
  bool flips(const Vec3f& wo) const { return transmission_ == 0 && wo.z < 0; }
  static DeltaLobes<N> mirrored(DeltaLobes<N> d) {
    for (int i = 0; i < d.count; ++i) d.lobes[i].wi = -d.lobes[i].wi;
    return d;
  }

  float diffuse_weight() const { return (1 - metallic_) * (1 - transmission_); }

  float E(float mu) const { return specular_ * SpecularAlbedo::table().E(std::abs(mu), alpha_, eta_, compensated_); }
  float coupling(const Vec3f& wo, const Vec3f& wi) const {
    return e_avg_ < 1 ? (1 - E(wo.z)) * (1 - E(wi.z)) / (1 - e_avg_) : 0.f;
  }

  // Probabilities of sampling the metal, the dielectric interface and the diffuse base: each
  // lobe's share of the light reflected towards wo.
  // Σ (probability of lobe) × (its pdf), for the probabilities of wo (not flipped).
  float mixture_pdf(const Vec3f& wo, const Vec3f& wi, const std::array<float, 3>& p) const {
    float r = p[0] * metal_.pdf(wo, wi) + p[1] * dielectric_.pdf(wo, wi);
    if (same_hemisphere(wo, wi)) r += p[2] * cosine_hemisphere_pdf(abs_cos_theta(wi));
    return r;
  }

  std::array<float, 3> lobe_probabilities(const Vec3f& wo) const {
    const float e = E(wo.z);
    std::array<float, 3> w = {metallic_, (1 - metallic_) * (e + transmission_ * (1 - e)),
                              diffuse_weight() * (1 - e) * std::max(albedo_.average(), 0.f)};
    const float sum = w[0] + w[1] + w[2];
    if (!(sum > 0)) return {0, 1, 0};
    for (float& x : w) x /= sum;
    return w;
  }

  // A delta sample of one lobe, as a sample of the mixture.
  static BsdfSample<N> scaled(BsdfSample<N> s, float weight, float probability) {
    s.f *= weight;
    s.pdf *= probability;
    return s;
  }

  float metallic_, transmission_;
  ConductorBsdf<N> metal_;
  DielectricBsdf<N> dielectric_;
  SampledSpectrum<N> albedo_;
  float alpha_, eta_, specular_;
  bool compensated_;
  float e_avg_;
};

}  // namespace prism
