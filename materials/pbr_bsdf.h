#pragma once
// glTF's metallic-roughness model, physically (glTF 2.0 Appendix B; KHR_materials_transmission):
//   f = m · f_metal + (1 − m) · [ f_dielectric + (1 − t) · ((1 − d) f_diffuse + d f_diffuse_t) ]
// m = metallic, t = transmission, d = diffuse transmission; f_metal a conductor, f_dielectric the
// dielectric interface (its reflection, and its transmission weighted by t), f_diffuse the
// Lambertian base under the specular layer, coupled to it so that the whole stays
// energy-consistent and reciprocal:
//   f_diffuse = ρ/π · (1 − E(μ_o)) (1 − E(μ_i)) / (1 − E_avg)      (see SpecularAlbedo)
// and f_diffuse_t the same with the diffuse-transmission colour, for wi on the far side
// (KHR_materials_diffuse_transmission: a thin wall, light leaves the other face diffusely).
// E is the albedo of the dielectric's lobe for its index η; when a specular colour or a thin
// film make the reflectance differ by lane, each lane couples with its own index η_λ: the
// coloured one (exact), or with a film an upper bound of the film's albedo, which no single index
// gives (the film's reflectance rises above any interface's somewhere towards grazing): the
// albedo of the interface of the film's peak reflectance at normal incidence (a quarter-wave
// layer's, n_f²/η) plus the white lobe's times x, the most the film's reflectance exceeds that
// interface's at any angle (film_reflectance_excess, thin_film.h):
//   E_λ(μ) = E(μ, η_λ) + x_λ E_white(μ),  so that the film's albedo ≤ E_λ and the whole ≤ 1.
// Sampled by choosing a lobe with probability ∝ its albedo seen from wo, then sampling it; f and
// pdf of non-delta directions are those of the whole mixture (for MIS). Without transmission
// the surface is opaque and two-sided: seen from behind, it is the same as from the front.

#include <array>
#include <new>
#include <optional>

#include "core/base/warp.h"
#include "materials/conductor_bsdf.h"
#include "materials/dielectric_bsdf.h"
#include "materials/specular_albedo.h"

namespace prism {

// Extensions = false compiles the plain metallic-roughness model, true adds diffuse
// transmission and the per-lane reflectance of the glTF extensions (LayeredBsdf's base).
template <int N, bool Extensions = false>
class PbrBsdf {
 public:
  // The extensions' parts: diffuse transmission, and the indices of the lanes when they reflect
  // differently (specular colour, thin film).
  struct Extras {
    float diffuse_transmission = 0;
    SampledSpectrum<N> transmitted_albedo{0.f};
    std::optional<SampledSpectrum<N>> lane_etas;
    std::optional<SampledSpectrum<N>> lane_excess;  // x_λ of a film (see the header)
  };

  // alpha, eta, specular and compensated must be those of the dielectric (they pick its albedo E).
  // `metal` and `dielectric` are callables that make the two lobes, so that each is built where it
  // is kept: a copy of a lobe just built read what was still being written (a stalled load).
  template <typename MakeMetal, typename MakeDielectric>
  PbrBsdf(float metallic, const MakeMetal& metal, const MakeDielectric& dielectric, float transmission,
          const SampledSpectrum<N>& albedo, float alpha, float eta, float specular, bool compensated,
          const Extras* extras = nullptr)
      : metallic_(metallic),
        transmission_(transmission),
        metal_(metal()),
        dielectric_(dielectric()),
        albedo_(albedo),
        specular_(specular),
        compensated_(compensated),
        roughness_(SpecularAlbedo::roughness(alpha)),
        albedo_curve_(SpecularAlbedo::table().curve(roughness_, eta, compensated)) {
    if constexpr (Extensions)
      if (extras) extras_.emplace(*extras, specular, roughness_, compensated);
  }

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

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const { return eval(wo, wi).f; }
  // Σ (probability of lobe) × (its pdf), without the lobes' values: what eval(wo, wi).pdf sums.
  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    if (flips(wo)) return pdf(-wo, -wi);
    const auto p = lobe_probabilities(E_o(wo.z));
    float r = 0.f;
    if (metallic_ > 0 && p[0] > 0) r += p[0] * metal_.pdf(wo, wi);
    if (metallic_ < 1 && p[1] > 0) r += p[1] * dielectric_.pdf(wo, wi);
    const float cosine_pdf = cosine_hemisphere_pdf(abs_cos_theta(wi));
    if (same_hemisphere(wo, wi))
      r += p[2] * cosine_pdf;
    else if constexpr (Extensions)
      r += p[3] * cosine_pdf;
    return r;
  }
  BsdfEval<N> eval(const Vec3f& wo, const Vec3f& wi) const {
    if (flips(wo)) return eval(-wo, -wi);
    const float e_o = E_o(wo.z);
    return mixture(wo, wi, lobe_probabilities(e_o), e_o);
  }

  // Every return names s, which is then made where the caller keeps it (NRVO), and the lobe's
  // sample is made in it: returned through a copy, the sample's narrow stores were read back at once
  // with wide loads (a stalled load in every sample, as renderer.cpp's camera rays were).
  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f u) const {
    std::optional<BsdfSample<N>> s;
    if (flips(wo)) {
      s = sample_f(-wo, uc, u);
      if (s) s->wi = -s->wi;
      return s;
    }
    const float e_o = E_o(wo.z);
    const auto p = lobe_probabilities(e_o);
    // The lobe is chosen by u.x (within_lobe); uc stays for the lobe's own choice. A delta sample
    // of one lobe is a sample of the mixture scaled by the lobe's weight and probability.
    std::optional<Sampled> sampled;
    const auto lobe_sample = [&](int lobe, const auto& bsdf, float weight, float probability) {
      ::new (&s) std::optional<BsdfSample<N>>(bsdf.sample_f(wo, uc, u));
      if (!s) return;
      if (s->specular) {
        s->f *= weight;
        s->pdf *= probability;
      } else {
        sampled = Sampled{lobe, {s->f, s->pdf}};  // its own f and pdf, not evaluated again
      }
    };
    if (u.x < p[0]) {
      u.x = within_lobe(u.x, 0, p[0]);
      lobe_sample(0, metal_, metallic_, p[0]);
    } else if (u.x < p[0] + p[1]) {
      u.x = within_lobe(u.x, p[0], p[1]);
      lobe_sample(1, dielectric_, 1 - metallic_, p[1]);
    } else {  // the diffuse base: reflected (p[2]) or transmitted to the far side (p[3])
      const bool far_side = Extensions && u.x >= 1 - p[3];
      u.x = within_lobe(u.x, far_side ? 1 - p[3] : p[0] + p[1], far_side ? p[3] : p[2]);
      Vec3f wi = sample_cosine_hemisphere(u);
      if ((wo.z < 0) != far_side) wi.z = -wi.z;
      s = BsdfSample<N>{SampledSpectrum<N>{}, wi, 0.f, false, far_side};
    }
    if (!s || s->specular) return s;
    take_mixture(s, mixture(wo, s->wi, p, e_o, sampled));
    return s;
  }

 private:
  bool flips(const Vec3f& wo) const { return transmission_ == 0 && wo.z < 0; }
  static DeltaLobes<N> mirrored(DeltaLobes<N> d) {
    for (int i = 0; i < d.count; ++i) d.lobes[i].wi = -d.lobes[i].wi;
    return d;
  }

  float diffuse_weight() const { return (1 - metallic_) * (1 - transmission_); }
  float diffuse_transmission() const {
    if constexpr (Extensions)
      if (extras_) return extras_->diffuse_transmission;
    return 0.f;
  }

  float E(float mu) const { return specular_ * SpecularAlbedo::E(albedo_curve_, std::abs(mu)); }
  // E(μ_o), kept for the next evaluation from the same wo (a path evaluates the BSDF of one hit
  // from one wo: towards its light samples and its BSDF sample).
  float E_o(float mu) const {
    mu = std::abs(mu);
    if (mu != outgoing_.mu) outgoing_ = {mu, E(mu), false, {}};
    return outgoing_.e;
  }
  // E_o's record completed with each lane's E(μ_o) and the white lobe's, for the lanes' coupling.
  // (Called only with the extensions' per-lane coupling.)
  const auto& lanes_outgoing(float mu) const {
    E_o(mu);
    if (!outgoing_.lanes) {
      outgoing_.at_lanes =
          SpecularAlbedo::table().at_lanes(outgoing_.mu, roughness_, extras_->lanes->eta, compensated_);
      outgoing_.lanes = true;
    }
    return outgoing_;
  }
  // The coupling factor (1 − E(μ_o))(1 − E(μ_i)) / (1 − E_avg): one value, or one per lane;
  // e_o = E(μ_o), found with the lobe probabilities.
  float scalar_coupling(float e_o, const Vec3f& wi) const {
    const float e_avg = specular_ * albedo_curve_.average;
    return e_avg < 1 ? (1 - e_o) * (1 - E(wi.z)) / (1 - e_avg) : 0.f;
  }
  auto coupling(const Vec3f& wo, float e_o, const Vec3f& wi) const {
    if constexpr (!Extensions) {
      return scalar_coupling(e_o, wi);
    } else {
      if (!extras_ || !extras_->lanes) return SampledSpectrum<N>(scalar_coupling(e_o, wi));
      const LaneCoupling& lanes = *extras_->lanes;
      // Each lane's E(μ) at its own index (before specular_) and the white lobe's; what μ_o gives, once per wo.
      const SpecularAlbedo::AtLanes<N>& o = lanes_outgoing(wo.z).at_lanes;
      const SpecularAlbedo::AtLanes<N> in =
          SpecularAlbedo::table().at_lanes(std::abs(wi.z), roughness_, lanes.eta, compensated_);
      const std::array<float, N>& lane_e_o = o.e;
      const std::array<float, N>& lane_e_i = in.e;
      const float white_o = o.white, white_i = in.white;
      // 0 where E_avg ≥ 1: a factor 0 or 1 and a divisor chosen per lane in a loop of their own,
      // so that the lanes' loop has no branch and runs on all lanes at once (SIMD).
      std::array<float, N> divisor, kept;
      for (int i = 0; i < N; ++i) {
        const float rest = 1 - lanes.e_avg[i];
        divisor[i] = rest > 0 ? rest : 1.f, kept[i] = rest > 0 ? 1.f : 0.f;
      }
      SampledSpectrum<N> c;
      for (int i = 0; i < N; ++i)
        c[i] = std::max(0.f, 1 - specular_ * (lane_e_o[i] + lanes.excess[i] * white_o)) *
               std::max(0.f, 1 - specular_ * (lane_e_i[i] + lanes.excess[i] * white_i)) / divisor[i] * kept[i];
      return c;
    }
  }

  // The lobe (0 the metal, 1 the dielectric) a non-delta sample came from, with its own f and pdf.
  struct Sampled {
    int lobe;
    BsdfEval<N> eval;
  };

  // f and Σ (probability of lobe) × (its pdf), for wo (not flipped), the probabilities p of wo and
  // e_o = E(μ_o); the lobe a sample came from is not evaluated again. Lobes of weight 0 are not
  // evaluated (most materials are not half metal).
  BsdfEval<N> mixture(const Vec3f& wo, const Vec3f& wi, const std::array<float, 4>& p, float e_o,
                      const std::optional<Sampled>& sampled = {}) const {
    const auto lobe = [&](int i, const auto& bsdf) {
      return sampled && sampled->lobe == i ? sampled->eval : lobe_eval<N>(bsdf, wo, wi);
    };
    BsdfEval<N> r{SampledSpectrum<N>(0.f), 0.f};
    if (metallic_ > 0) {
      const BsdfEval<N> m = lobe(0, metal_);
      r.f += m.f * metallic_;
      if (p[0] > 0) r.pdf += p[0] * m.pdf;
    }
    if (metallic_ < 1) {
      const BsdfEval<N> d = lobe(1, dielectric_);
      r.f += d.f * (1 - metallic_);
      if (p[1] > 0) r.pdf += p[1] * d.pdf;
    }
    const float cosine_pdf = cosine_hemisphere_pdf(abs_cos_theta(wi));
    if (same_hemisphere(wo, wi)) {
      r.pdf += p[2] * cosine_pdf;
      if (diffuse_weight() > 0)
        r.f += albedo_ * (coupling(wo, e_o, wi) * (diffuse_weight() * (1 - diffuse_transmission()) * kInvPi));
    } else if constexpr (Extensions) {
      r.pdf += p[3] * cosine_pdf;
      if (diffuse_weight() > 0 && diffuse_transmission() > 0)
        r.f += extras_->transmitted_albedo *
               (coupling(wo, e_o, wi) * (diffuse_weight() * diffuse_transmission() * kInvPi));
    }
    return r;
  }

  // Probabilities of sampling the metal, the dielectric interface, the diffuse base and its
  // transmission: each lobe's share of the light scattered towards wo, e = E(μ_o).
  std::array<float, 4> lobe_probabilities(float e) const {
    const float diffuse = diffuse_weight() * (1 - e);
    std::array<float, 4> w = {metallic_, (1 - metallic_) * (e + transmission_ * (1 - e)),
                              diffuse * (1 - diffuse_transmission()) * std::max(albedo_.average(), 0.f), 0.f};
    if constexpr (Extensions)
      if (extras_)
        w[3] = diffuse * extras_->diffuse_transmission * std::max(extras_->transmitted_albedo.average(), 0.f);
    const float sum = w[0] + w[1] + w[2] + w[3];
    if (!(sum > 0)) return {0, 1, 0, 0};
    for (float& x : w) x /= sum;
    return w;
  }

  // The lanes' own coupling: each lane's index placed on the albedo tables once, its film excess
  // x_λ, and its E_avg (see the header). Built where it is kept, as the lobes are.
  struct LaneCoupling {
    SpecularAlbedo::Lanes<N> eta;
    SampledSpectrum<N> excess, e_avg;
    LaneCoupling(const Extras& extras, float specular, const SpecularAlbedo::Roughness& roughness, bool compensated)
        : eta(extras.lane_etas->lanes()), excess(extras.lane_excess.value_or(SampledSpectrum<N>(0.f))) {
      const SpecularAlbedo& table = SpecularAlbedo::table();
      const float white_average = extras.lane_excess ? table.white_average(roughness) : 0.f;
      const std::array<float, N> average = table.average(roughness, eta, compensated);
      for (int i = 0; i < N; ++i) e_avg[i] = specular * (average[i] + excess[i] * white_average);
    }
  };
  struct Parts {
    float diffuse_transmission;
    SampledSpectrum<N> transmitted_albedo;
    std::optional<LaneCoupling> lanes;
    Parts(const Extras& extras, float specular, const SpecularAlbedo::Roughness& roughness, bool compensated)
        : diffuse_transmission(extras.diffuse_transmission), transmitted_albedo(extras.transmitted_albedo) {
      if (extras.lane_etas) lanes.emplace(extras, specular, roughness, compensated);
    }
  };

  float metallic_, transmission_;
  ConductorBsdf<N, Extensions> metal_;
  DielectricBsdf<N, Extensions> dielectric_;
  SampledSpectrum<N> albedo_;
  float specular_;
  bool compensated_;
  SpecularAlbedo::Roughness roughness_;  // the specular lobe's α, on the albedo tables
  SpecularAlbedo::Curve albedo_curve_;   // its E(μ) and E_avg for its α and η
  [[no_unique_address]] OptionalPart<Extensions, Parts> extras_;
  struct Outgoing {  // what depends on wo alone (E_o), for the last |μ_o| asked
    float mu = -1;   // none yet
    float e;
    bool lanes;                           // the lanes' coupling: at_lanes found
    SpecularAlbedo::AtLanes<N> at_lanes;  // each lane's E(μ_o) (before specular_), and the white lobe's
  };
  mutable Outgoing outgoing_;  // a cache: safe because a Bsdf is built and used within one thread
};

}  // namespace prism
