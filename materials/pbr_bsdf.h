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

#include "core/base/frame.h"
#include "core/base/warp.h"
#include "materials/conductor_bsdf.h"
#include "materials/dielectric_bsdf.h"
#include "materials/sheen_albedo.h"
#include "materials/sheen_bsdf.h"
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
    const BsdfEval<N> e = mixture(wo, s->wi, p, e_o, sampled);
    if (!(e.pdf > 0)) {
      s.reset();
      return s;
    }
    s->f = e.f;
    s->pdf = e.pdf;
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

// The glTF base under its top layers, KHR_materials_sheen and KHR_materials_clearcoat, each
// layered by albedo scaling (Kulla & Conty 2017; Estevez & Kulla 2017 §3): a layer lets through
// what its own lobe does not reflect, 1 − w·E(μ), w its weight, E its directional albedo.
//   f = c f_coat + T_c(μ_o) T_c(μ_i) [ f_sheen + S(μ_o, μ_i) f_base ]
//   T_c(μ) = 1 − c E_coat(μ)                     the coat (index 1.5, GGX) crossed on the way in and out
//   S = min(1 − s E_sheen(μ_o), 1 − s E_sheen(μ_i))   KHR_materials_sheen's scaling, s = max of the colour
// c = clearcoat factor. Each factor is ≤ 1 − (that layer's albedo towards wo), so the albedo
// never exceeds 1; all are symmetric in wo and wi, so the whole is reciprocal. Light the coat
// reflects back down is not followed (as in the extension). The coat has its own normal (the
// clearcoat normal texture): its lobe and its μ are taken in that frame, and it reflects nothing
// towards directions below it. Sampled by choosing the coat, the sheen or the base with
// probability ∝ its share towards wo; f and pdf are the mixture's.
template <int N>
class LayeredBsdf {
 public:
  struct Coat {
    float weight, alpha, eta;  // clearcoat factor, GGX α (isotropic), index relative to the front medium
    Vec3f normal;              // in the shading frame
    bool compensated = true;   // multiple scattering added back, as the base's (Turquin 2019)
  };
  struct Sheen {
    SampledSpectrum<N> color;
    float alpha;
  };

  // The base is built in place from PbrBsdf's arguments (it is large: copying it cost as much as building it).
  template <typename... BaseArguments>
  LayeredBsdf(const std::optional<Coat>& coat, const std::optional<Sheen>& sheen, const BaseArguments&... base)
      : base_(base...),
        coat_(TrowbridgeReitz(coat ? coat->alpha : 0), coat ? coat->eta : 1, SampledSpectrum<N>(1.f), false, 0, 1,
              coat && coat->compensated),
        coat_weight_(coat ? coat->weight : 0),
        coat_albedo_(coat ? SpecularAlbedo::table().curve(SpecularAlbedo::roughness(coat->alpha),
                                                          std::max(coat->eta, 1.f), coat->compensated)
                          : SpecularAlbedo::Curve{}),  // no coat: weight 0
        coat_tilted_(coat && coat->normal != Vec3f(0, 0, 1)),
        coat_frame_(Frame::from_z(coat_tilted_ ? coat->normal : Vec3f(0, 0, 1))),
        sheen_roughness_(SheenRoughness::of(sheen ? sheen->alpha : 1)),
        sheen_(sheen ? sheen->color : SampledSpectrum<N>(0.f), sheen_roughness_),
        sheen_weight_(sheen ? sheen->color.max() : 0) {}

  bool is_specular() const {
    return base_.is_specular() && sheen_weight_ == 0 && (coat_weight_ == 0 || coat_.is_specular());
  }

  DeltaLobes<N> delta_lobes(const Vec3f& wo) const {
    DeltaLobes<N> d;
    if (coat_weight_ > 0)
      for (const DeltaLobe<N>& l : coat_.delta_lobes(to_coat(wo, wo)))
        if (const Vec3f wi = from_coat(wo, l.wi); same_hemisphere(wo, wi))
          d.add({wi, l.weight * coat_weight_, false, 1.f});
    for (const DeltaLobe<N>& l : base_.delta_lobes(wo))
      d.add({l.wi, l.weight * base_scale(outgoing(wo), l.wi), l.transmission, l.eta});
    return d;
  }

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const { return eval(wo, wi).f; }
  // Σ (probability of layer) × (its pdf), without the layers' values: what eval(wo, wi).pdf sums.
  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    const auto p = layer_probabilities(outgoing(wo));
    float r = p[2] * base_.pdf(wo, wi);
    if (coat_weight_ > 0 && same_hemisphere(wo, wi) && p[0] > 0)
      r += p[0] * coat_.pdf(to_coat(wo, wo), to_coat(wo, wi));
    if (p[1] > 0) r += p[1] * sheen_.pdf(wo, wi);
    return r;
  }
  BsdfEval<N> eval(const Vec3f& wo, const Vec3f& wi) const {
    const Outgoing& o = outgoing(wo);
    return mixture(wo, wi, o, layer_probabilities(o));
  }

  // Every return names s, each layer's sample made in it (as PbrBsdf::sample_f, for the same reason).
  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f u) const {
    const Outgoing& o = outgoing(wo);
    const auto p = layer_probabilities(o);
    std::optional<BsdfSample<N>> s;
    int layer = 0;
    // The layer is chosen by u.x (within_lobe), as the base chooses its lobe; uc stays for theirs.
    if (u.x < p[0]) {
      u.x = within_lobe(u.x, 0, p[0]);
      ::new (&s) std::optional<BsdfSample<N>>(coat_.sample_f(to_coat(wo, wo), uc, u));
      if (!s) return s;
      s->wi = from_coat(wo, s->wi);
      if (!same_hemisphere(wo, s->wi)) {
        s.reset();
        return s;
      }
      if (s->specular) {
        s->f *= coat_weight_;
        s->pdf *= p[0];
        return s;
      }
      // A tilted coat's own f and pdf are those at wi back in its frame, as eval finds them (the
      // round trip through the frame rounds).
      if (coat_tilted_) {
        const BsdfEval<N> c = coat_.eval(to_coat(wo, wo), to_coat(wo, s->wi));
        s->f = c.f, s->pdf = c.pdf;
      }
    } else if (u.x < p[0] + p[1]) {
      u.x = within_lobe(u.x, p[0], p[1]);
      ::new (&s) std::optional<BsdfSample<N>>(sheen_.sample_f(wo, 0, u));
      layer = 1;
    } else {
      u.x = within_lobe(u.x, p[0] + p[1], p[2]);
      ::new (&s) std::optional<BsdfSample<N>>(base_.sample_f(wo, uc, u));
      if (!s) return s;
      if (s->specular) {
        s->f *= base_scale(o, s->wi);
        s->pdf *= p[2];
        return s;
      }
      layer = 2;
    }
    if (!s) return s;
    // The sampled layer's own f and pdf come with its sample.
    const BsdfEval<N> e = mixture(wo, s->wi, o, p, Sampled{layer, {s->f, s->pdf}});
    if (!(e.pdf > 0)) {
      s.reset();
      return s;
    }
    s->f = e.f;
    s->pdf = e.pdf;
    return s;
  }

 private:
  // w in the coat's frame, seen from wo's side taken up (the coat is evaluated above the
  // surface), and back.
  Vec3f to_coat(const Vec3f& wo, const Vec3f& w) const {
    const Vec3f v = wo.z < 0 ? -w : w;
    return coat_tilted_ ? coat_frame_.to_local(v) : v;
  }
  Vec3f from_coat(const Vec3f& wo, const Vec3f& w) const {
    const Vec3f v = coat_tilted_ ? coat_frame_.to_world(w) : w;
    return wo.z < 0 ? -v : v;
  }

  // The coat's albedo towards w (none from below the coat's own horizon).
  float coat_E(const Vec3f& w) const {
    const float mu = (coat_tilted_ ? dot(w.z < 0 ? -w : w, coat_frame_.z) : std::abs(w.z));
    return mu > 0 ? coat_weight_ * SpecularAlbedo::E(coat_albedo_, mu) : 0.f;
  }
  float sheen_E(float mu) const { return sheen_weight_ * SheenAlbedo::E(sheen_roughness_.albedo, std::abs(mu)); }
  // The coat's and the sheen's albedos towards wo, kept for the next evaluation from the same wo.
  struct Outgoing {
    Vec3f wo{0, 0, 0};  // none yet
    float coat, sheen;
  };
  const Outgoing& outgoing(const Vec3f& wo) const {
    if (wo != outgoing_.wo)
      outgoing_ = {wo, coat_weight_ > 0 ? coat_E(wo) : 0.f, sheen_weight_ > 0 ? sheen_E(wo.z) : 0.f};
    return outgoing_;
  }
  // The layers' scalings of what lies beneath them, for wo's albedos o.
  float coat_scale(const Outgoing& o, const Vec3f& wi) const {
    return coat_weight_ > 0 ? (1 - o.coat) * (1 - coat_E(wi)) : 1.f;
  }
  float sheen_scale(const Outgoing& o, const Vec3f& wi) const {
    return sheen_weight_ > 0 ? 1 - std::max(o.sheen, sheen_E(wi.z)) : 1.f;
  }
  float base_scale(const Outgoing& o, const Vec3f& wi) const { return coat_scale(o, wi) * sheen_scale(o, wi); }

  // The layer (0 the coat, 1 the sheen, 2 the base) a non-delta sample came from, with its own f and pdf.
  struct Sampled {
    int layer;
    BsdfEval<N> eval;
  };

  // f and Σ (probability of layer) × (its pdf), for wo's albedos o and probabilities p; the layer a
  // sample came from is not evaluated again.
  BsdfEval<N> mixture(const Vec3f& wo, const Vec3f& wi, const Outgoing& o, const std::array<float, 3>& p,
                      const std::optional<Sampled>& sampled = {}) const {
    const auto layer = [&](int i, const auto& evaluate) {
      return sampled && sampled->layer == i ? sampled->eval : evaluate();
    };
    const BsdfEval<N> base = layer(2, [&] { return base_.eval(wo, wi); });
    BsdfEval<N> r{base.f * sheen_scale(o, wi), p[2] * base.pdf};
    std::optional<BsdfEval<N>> sheen;  // none at weight 0, where p[1] = 0 too
    if (sheen_weight_ > 0) {
      sheen = layer(1, [&] { return BsdfEval<N>{sheen_.f(wo, wi), sheen_.pdf(wo, wi)}; });
      r.f += sheen->f;
    }
    r.f *= coat_scale(o, wi);
    if (coat_weight_ > 0 && same_hemisphere(wo, wi)) {
      const BsdfEval<N> c = layer(0, [&] { return coat_.eval(to_coat(wo, wo), to_coat(wo, wi)); });
      r.f += c.f * coat_weight_;
      if (p[0] > 0) r.pdf += p[0] * c.pdf;
    }
    if (p[1] > 0) r.pdf += p[1] * sheen->pdf;
    return r;
  }

  // The coat's, the sheen's and the base's shares of the light scattered towards wo, from its albedos o.
  std::array<float, 3> layer_probabilities(const Outgoing& o) const {
    const float c = o.coat, t = 1 - c, s = o.sheen;
    std::array<float, 3> w = {c, t * s, t * (1 - s)};
    const float sum = w[0] + w[1] + w[2];
    if (!(sum > 0)) return {0, 0, 1};
    for (float& x : w) x /= sum;
    return w;
  }

  PbrBsdf<N, true> base_;
  DielectricBsdf<N> coat_;
  float coat_weight_;
  SpecularAlbedo::Curve coat_albedo_;  // the coat's E(μ), found once
  bool coat_tilted_;
  Frame coat_frame_;
  SheenRoughness sheen_roughness_;  // what the sheen's α gives (its albedo along μ: .albedo)
  SheenBsdf<N> sheen_;
  float sheen_weight_;
  mutable Outgoing outgoing_;  // a cache: safe because a Bsdf is built and used within one thread
};

}  // namespace prism
