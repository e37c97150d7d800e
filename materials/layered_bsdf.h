#pragma once
// LayeredBsdf: the glTF base (PbrBsdf with the extensions' parts) under its top layers,
// KHR_materials_sheen and KHR_materials_clearcoat, each layered by albedo scaling (Kulla & Conty
// 2017; Estevez & Kulla 2017 §3): a layer lets through what its own lobe does not reflect,
// 1 − w·E(μ), w its weight, E its directional albedo.
//   f = c f_coat + T_c(μ_o) T_c(μ_i) [ f_sheen + S(μ_o, μ_i) f_base ]
//   T_c(μ) = 1 − c E_coat(μ)                     the coat (index 1.5, GGX) crossed on the way in and out
//   S = min(1 − s E_sheen(μ_o), 1 − s E_sheen(μ_i))   KHR_materials_sheen's scaling, s = max of the colour
// c = clearcoat factor. Each factor is ≤ 1 − (that layer's albedo towards wo), so the albedo
// never exceeds 1; all are symmetric in wo and wi, so the whole is reciprocal. Light the coat
// reflects back down is not followed (as in the extension). The coat has its own normal (the
// clearcoat normal texture): its lobe and its μ are taken in that frame, and it reflects nothing
// towards directions below it. Sampled by choosing the coat, the sheen or the base with
// probability ∝ its share towards wo; f and pdf are the mixture's.

#include <array>
#include <new>
#include <optional>

#include "core/base/frame.h"
#include "materials/dielectric_bsdf.h"
#include "materials/pbr_bsdf.h"
#include "materials/sheen_albedo.h"
#include "materials/sheen_bsdf.h"
#include "materials/specular_albedo.h"

namespace prism {

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
    take_mixture(s, mixture(wo, s->wi, o, p, Sampled{layer, {s->f, s->pdf}}));
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
