#pragma once
// Dielectric interface, smooth or rough (Walter et al. 2007, "Microfacet Models for Refraction
// through Rough Surfaces"; pbrt-v4 §9.7): reflection with the exact Fresnel reflectance F and
// transmission with 1 − F, at the macro surface when smooth, at GGX microfacets m when rough:
//   f_r = D(m) G F / (4 |cos θ_o cos θ_i|),                         m ∝ wo + wi
//   f_t = D(m) G (1 − F) |(wi·m)(wo·m)| / (|cos θ_o cos θ_i| (wi·m + wo·m/η')²) / η'²,  m ∝ η' wi + wo
// where the last 1/η'² is the radiance scaling across the interface (Veach 1997, §5.2).
// Thin wall (a sheet with no interior): the two interfaces' inter-reflections sum to
// R' = R + T²R/(1 − R²) = 2R/(1 + R), T' = 1 − R' for each polarisation, s and p apart (a plane
// interface never turns one into the other), and unpolarised light reflects their mean; light
// leaves on the far side in the mirror image of the reflection lobe (straight through when
// smooth). (The sum over the unpolarised R, as pbrt-v4 §9.5.1 takes it, passes up to 0.022
// less light from 50° to 85° at η = 1.5.) Only the clear share of a wall (`transmission`) has
// a far face: an opaque wall is the one interface over its base (glTF materials without
// KHR_materials_volume are thin-walled, most of them opaque); a partly clear one is both, side
// by side (see reflected()).
// `transmission` ∈ [0, 1] weights the transmitted lobe (glTF's transmissionFactor; the rest
// of the light goes to a diffuse base elsewhere); `tint` colours transmitted light; `specular`
// scales the reflectance, s·F, leaving 1 − s·F to pass (KHR_materials_specular's factor).
// Per-lane reflectance (SpectralReflectance): KHR_materials_specular's colour, as the index η_λ
// whose exact F0 is the coloured one (F90 stays s), and a thin film (KHR_materials_iridescence)
// over the interface (compiled in with Extensions = true); without them every lane reflects alike.
// Multiple scattering between the microfacets (Turquin 2019, "Practical multiple scattering
// compensation for microfacet models"): the light a lossless rough interface loses, 1 − E(μ_o)
// with E its single-scattering R + T albedo (SpecularAlbedo::interface, from the side of wo; for a
// thin wall the white reflection albedo, and for a partly clear one each share's own: see
// partly_clear_reflection), is shared out in proportion to the lobes: f_ms = f / E(μ_o).
// A compensated lobe samples again where a visible normal sends wo to the wrong side
// (sample_tries.h), where the success probability is tabulated: for the interface with s = 1 and
// for a lossless reflection (thin walls, opaque faces); other lobes sample once. `compensate`
// false leaves the single-scattering lobes, sampled once. A specular colour's lanes are
// compensated with their own indices η_λ; make_bsdf leaves a thin film's lobes uncompensated (E
// of the filmed interface is not tabulated; dividing by the bare one's lets a film over rough
// glass reflect up to 1.5% more than it receives).

#include <cstdint>
#include <limits>
#include <optional>

#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "materials/sample_tries.h"
#include "materials/specular_albedo.h"
#include "materials/thin_film.h"

namespace prism {

template <int N>
struct Transmission {
  Vec3f wi;
  SampledSpectrum<N> weight;  // the transmitted share: transmission · tint · T, divided by η² when refracted
  float eta;                  // relative index crossed (1 for a thin wall)
};

// Per-lane changes to a dielectric's reflectance: the index its Fresnel reflectance follows
// (not the one that refracts), and a film over it.
template <int N>
struct SpectralReflectance {
  std::optional<SampledSpectrum<N>> eta;
  std::optional<FilmLanes<N>> film;
};

// One face's reflectance R (per lane, or one number) and what a thin wall's inter-reflections add
// to it, R' − R (0 for a solid interface).
template <typename S>
struct FaceReflectance {
  S R, sheet_excess;
};

template <int N, bool Extensions = false>
class DielectricBsdf {
 public:
  // eta = n_back / n_front (the index behind the shading normal over the one in front), one
  // value for all lanes: a λ-dependent index is one DielectricBsdf per lane (dispersive_bsdf.h)
  // or the hero's alone (make_hero_bsdf, for BDPT and VCM).
  DielectricBsdf(const TrowbridgeReitz& distribution, float eta, const SampledSpectrum<N>& tint, bool thin,
                 float transmission = 1.f, float specular = 1.f, bool compensate = true,
                 const OptionalPart<Extensions, SpectralReflectance<N>>& lanes = {})
      : distribution_(distribution),
        smooth_(distribution.effectively_smooth() || eta == 1),
        compensate_(compensate && !smooth_),
        roughness_(compensate_ ? SpecularAlbedo::roughness(distribution.alpha()) : SpecularAlbedo::Roughness{}),
        eta_(eta),
        tint_(tint),
        thin_(thin && transmission > 0),  // an opaque wall is the one interface over its base
        transmission_(transmission),
        specular_(specular),
        retries_(!compensate_ || !distribution.isotropic() ? Retries::kNone
                 : thin_ || transmission <= 0              ? Retries::kReflection
                 : transmission == 1 && specular == 1      ? Retries::kInterface
                                                           : Retries::kNone),
        lanes_(lanes) {}

  bool is_specular() const { return smooth_; }

  // Fresnel reflectance s·F of one face at a (micro)facet with cos θ = cos_theta (signed: < 0 from
  // behind), per lane, with a thin wall's sheet excess: what reflected() and transmitted() share out.
  FaceReflectance<SampledSpectrum<N>> fresnel(float cos_theta) const {
    const float c = thin_ ? std::abs(cos_theta) : cos_theta;
    FaceReflectance<SampledSpectrum<N>> face{SampledSpectrum<N>(0.f), SampledSpectrum<N>(0.f)};
    if constexpr (Extensions)
      if (lanes_) {
        const auto eta = [&](int i) { return lanes_->eta ? (*lanes_->eta)[i] : eta_; };
        if (lanes_->film) face.R = lanes_->film->reflectance(c, eta) * specular_;
        if (lanes_->film && !thin_) return face;
        for (int i = 0; i < N; ++i) {
          const FresnelReflectance bare = fresnel_dielectric_polarized(c, eta(i));
          if (!lanes_->film) face.R[i] = specular_ * bare.R;
          // A film's reflectance is shared between s and p as the bare interface's is.
          if (thin_) face.sheet_excess[i] = sheet_excess(face.R[i], bare);
        }
        return face;
      }
    const FresnelReflectance bare = fresnel_dielectric_polarized(c, eta_);
    face.R = SampledSpectrum<N>(specular_ * bare.R);
    if (thin_) face.sheet_excess = SampledSpectrum<N>(sheet_excess(specular_ * bare.R, bare));
    return face;
  }
  // The one face's reflectance that picks reflection over transmission when sampling (shares()):
  // that of every lane alike (a per-lane one would cost a film per pdf; any choice is unbiased).
  FaceReflectance<float> selection(float cos_theta) const {
    const FresnelReflectance bare = fresnel_dielectric_polarized(thin_ ? std::abs(cos_theta) : cos_theta, eta_);
    return {specular_ * bare.R, thin_ ? sheet_excess(specular_ * bare.R, bare) : 0.f};
  }

  // Smooth interface: the reflected share, and the transmitted direction and share.
  SampledSpectrum<N> reflectance(const Vec3f& wo) const { return reflected(fresnel(cos_theta(wo))); }
  std::optional<Transmission<N>> transmission(const Vec3f& wo) const {
    return transmission(wo, fresnel(cos_theta(wo)));
  }
  // From the face's reflectance F there.
  std::optional<Transmission<N>> transmission(const Vec3f& wo, const FaceReflectance<SampledSpectrum<N>>& F) const {
    if (transmission_ <= 0 || F.R.min() >= 1) return std::nullopt;
    const SampledSpectrum<N> T = transmitted(F) * transmission_;
    if (thin_) return Transmission<N>{-wo, tint_ * T, 1.f};
    const auto refraction = refract(wo, {0, 0, 1}, eta_);
    if (!refraction) return std::nullopt;
    return Transmission<N>{refraction->wt, tint_ * T / sqr(refraction->eta_p), refraction->eta_p};
  }

  DeltaLobes<N> delta_lobes(const Vec3f& wo) const {
    DeltaLobes<N> d;
    if (!smooth_ || wo.z == 0) return d;
    const auto F = fresnel(cos_theta(wo));
    d.add({Vec3f(-wo.x, -wo.y, wo.z), reflected(F), false, 1.f});
    if (const auto t = transmission(wo, F)) d.add({t->wi, t->weight, true, t->eta});
    return d;
  }

  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi) const {
    const auto h = half_vector(wo, wi);
    return h ? f(wo, wi, *h, facet(wo, wi, *h), fresnel(dot(wo, h->wm))) : SampledSpectrum<N>(0.f);
  }

  float pdf(const Vec3f& wo, const Vec3f& wi) const {
    const auto h = half_vector(wo, wi);
    return h ? pdf(wo, wi, *h, facet(wo, wi, *h), selection(dot(wo, h->wm))) : 0.f;
  }

  // f and pdf with one half vector, one D(m) and Λ(wo), and one Fresnel reflectance.
  BsdfEval<N> eval(const Vec3f& wo, const Vec3f& wi) const {
    const auto h = half_vector(wo, wi);
    if (!h) return {SampledSpectrum<N>(0.f), 0.f};
    const TrowbridgeReitz::Facet t = facet(wo, wi, *h);
    const float c = dot(wo, h->wm);
    const auto F = fresnel(c);
    return {f(wo, wi, *h, t, F), pdf(wo, wi, *h, t, selection(c, F))};
  }

  std::optional<BsdfSample<N>> sample_f(const Vec3f& wo, float uc, Vec2f u) const {
    if (wo.z == 0) return std::nullopt;
    if (smooth_) return sample_smooth(wo, uc);
    for (int k = 1;; ++k) {
      if (const auto d = sample_direction(wo, uc, u)) {
        const BsdfEval<N> e = eval(wo, d->wi);
        if (!(e.pdf > 0)) return std::nullopt;
        return BsdfSample<N>{e.f, d->wi, e.pdf, false, d->transmitted, d->eta_p};
      }
      if (k >= tries(wo.z).count) return std::nullopt;
      sample_tries::next(uc, u);
    }
  }

 private:
  // Which success probability a failed sample's next try follows (see the header).
  enum class Retries : uint8_t { kNone, kReflection, kInterface };

  struct SampledDirection {
    Vec3f wi;
    bool transmitted;
    float eta_p;
  };
  // One try: a visible normal, then reflection or transmission by their shares; nothing when the
  // direction falls on the wrong side.
  std::optional<SampledDirection> sample_direction(const Vec3f& wo, float uc, Vec2f u) const {
    const Vec3f wm = distribution_.sample_visible_normal(wo, u);
    const auto [R, T] = shares(selection(dot(wo, wm)));
    if (R + T <= 0) return std::nullopt;
    if (uc < R / (R + T)) {
      const Vec3f wi = reflect(wo, wm);
      if (!same_hemisphere(wo, wi)) return std::nullopt;
      return SampledDirection{wi, false, 1.f};
    }
    if (thin_) {
      const Vec3f r = reflect(wo, wm);
      const Vec3f wi(r.x, r.y, -r.z);
      if (same_hemisphere(wo, wi)) return std::nullopt;
      return SampledDirection{wi, true, 1.f};
    }
    const auto refraction = refract(wo, wm, eta_);
    if (!refraction || same_hemisphere(wo, refraction->wt) || refraction->wt.z == 0) return std::nullopt;
    return SampledDirection{refraction->wt, true, refraction->eta_p};
  }

  struct HalfVector {
    Vec3f wm;
    bool reflection;
    float eta_p;
  };

  // D, G and G1(wo) at the half vector h (the far-side lobe's wi is mirrored, which leaves Λ(wi) as it is).
  TrowbridgeReitz::Facet facet(const Vec3f& wo, const Vec3f& wi, const HalfVector& h) const {
    return distribution_.facet(wo, wi, h.wm);
  }

  // f at the half vector h with its facet's terms t and the Fresnel reflectance F there,
  // compensated (see the header).
  SampledSpectrum<N> f(const Vec3f& wo, const Vec3f& wi, const HalfVector& h, const TrowbridgeReitz::Facet& t,
                       const FaceReflectance<SampledSpectrum<N>>& F) const {
    if (!compensate_) return single_scattering(wo, wi, h, t, F);
    if (thin_ && transmission_ < 1 && h.reflection) return partly_clear_reflection(wo, wi, t, F);
    if constexpr (Extensions)
      if (lanes_ && lanes_->eta)  // each lane's reflectance follows its own index: so does its E
        return single_scattering(wo, wi, h, t, F) / lanes_outgoing_albedo(wo.z);
    return single_scattering(wo, wi, h, t, F) * outgoing(wo.z).inverse_e;
  }

  // The selection share from the face's reflectance F at the same facet: without per-lane
  // reflectance, every lane of F is that share.
  FaceReflectance<float> selection(float cos_theta, const FaceReflectance<SampledSpectrum<N>>& F) const {
    if constexpr (Extensions)
      if (lanes_) return selection(cos_theta);
    return {F.R[0], F.sheet_excess[0]};
  }

  // pdf at the half vector h with its facet's terms t, `face` the selection share there.
  float pdf(const Vec3f& wo, const Vec3f& wi, const HalfVector& h, const TrowbridgeReitz::Facet& t,
            const FaceReflectance<float>& face) const {
    const auto [R, T] = shares(face);
    if (R + T <= 0) return 0.f;
    const float tries = this->tries(wo.z).pdf_scale;
    if (h.reflection || thin_)  // the far side's lobe mirrors the reflection
      return TrowbridgeReitz::reflected_pdf(wo, t) * (h.reflection ? R : T) / (R + T) * tries;
    const float dwm_dwi = abs_dot(wi, h.wm) / sqr(dot(wi, h.wm) + dot(wo, h.wm) / h.eta_p);
    return TrowbridgeReitz::D_visible(wo, h.wm, t) * dwm_dwi * T / (R + T) * tries;
  }

  // The microfacet normal that takes wo to wi (facing +z), or nothing for a smooth surface,
  // grazing directions, or normals that face away from either direction.
  std::optional<HalfVector> half_vector(const Vec3f& wo, Vec3f wi) const {
    if (smooth_ || wo.z == 0 || wi.z == 0) return std::nullopt;
    const bool reflection = same_hemisphere(wo, wi);
    if (thin_ && !reflection) wi.z = -wi.z;  // the far-side lobe mirrors the reflection lobe
    const float eta_p = reflection || thin_ ? 1.f : (wo.z > 0 ? eta_ : 1 / eta_);
    const Vec3f m = wi * eta_p + wo;
    if (length_squared(m) == 0) return std::nullopt;
    const Vec3f wm = face_forward(normalize(m), Vec3f(0, 0, 1));
    if (dot(wm, wi) * wi.z < 0 || dot(wm, wo) * wo.z < 0) return std::nullopt;
    return HalfVector{wm, reflection, eta_p};
  }

  SampledSpectrum<N> single_scattering(const Vec3f& wo, const Vec3f& wi, const HalfVector& h,
                                       const TrowbridgeReitz::Facet& t,
                                       const FaceReflectance<SampledSpectrum<N>>& F) const {
    const float D = t.D;
    if (h.reflection) return reflected(F) * (D * t.G / std::abs(4 * wi.z * wo.z));
    const SampledSpectrum<N> T = tint_ * transmitted(F);
    if (thin_) return T * (transmission_ * D * t.G / std::abs(4 * wi.z * wo.z));  // G(wo, wi mirrored) = G(wo, wi)
    const float denom = sqr(dot(wi, h.wm) + dot(wo, h.wm) / h.eta_p) * wi.z * wo.z;
    const float ft = D * t.G * std::abs(dot(wi, h.wm) * dot(wo, h.wm) / denom);
    return T * (transmission_ * ft / sqr(h.eta_p));
  }

  // A partly clear wall's reflection, compensated share by share: the opaque share's (1 − t) F as
  // the one interface's (the albedo the diffuse base's coupling subtracts, SpecularAlbedo::E), the
  // sheet's t R' as the thin wall's. (The whole divided by the thin wall's white E let a rough white
  // wall return 1.02 of the light at roughness 1, t = 0.25.)
  SampledSpectrum<N> partly_clear_reflection(const Vec3f& wo, const Vec3f& wi, const TrowbridgeReitz::Facet& t,
                                             const FaceReflectance<SampledSpectrum<N>>& F) const {
    const SpecularAlbedo& table = SpecularAlbedo::table();
    const float mu = std::abs(wo.z), sheet = transmission_ / table.white(mu, roughness_);
    const float lobe = t.D * t.G / std::abs(4 * wi.z * wo.z);
    // The one interface's albedo: once for the index every lane follows, else each lane's for its
    // own, the tables read once at each η node the lanes span.
    const SampledSpectrum<N> interface = [&] {
      if constexpr (Extensions)
        if (lanes_ && lanes_->eta)
          return SampledSpectrum<N>(table.interface(SpecularAlbedo::direction(mu, roughness_),
                                                    SpecularAlbedo::Lanes<N>(lanes_->eta->lanes())));
      return SampledSpectrum<N>(table.interface(mu, roughness_, eta_));
    }();
    SampledSpectrum<N> f;
    for (int i = 0; i < N; ++i) {
      const float opaque = (1 - transmission_) / interface[i];
      f[i] = lobe * (opaque * F.R[i] + sheet * (F.R[i] + F.sheet_excess[i]));
    }
    return f;
  }

  // E(μ_o) of the white lossless lobes on wo's side (see the header).
  float single_scattering_albedo(float mu, float eta) const {
    const SpecularAlbedo& t = SpecularAlbedo::table();
    if (thin_) return t.white(std::abs(mu), roughness_);
    return t.interface(std::abs(mu), roughness_, mu > 0 ? eta : 1 / eta);
  }
  // What a compensated lobe needs of μ_o, kept for the last μ_o asked: a light sample and the
  // path's own sample are evaluated from the same wo.
  struct Outgoing {
    float mu = std::numeric_limits<float>::quiet_NaN();  // none yet
    float inverse_e = 0;                                 // 1 / E(μ_o) for the index every lane follows
    sample_tries::Tries tries = sample_tries::kOneTry;
  };
  const Outgoing& outgoing(float mu) const {
    if (!(mu == outgoing_.mu)) {
      outgoing_ = {mu, 1 / single_scattering_albedo(mu, eta_), sample_tries::kOneTry};
      const SpecularAlbedo& table = SpecularAlbedo::table();
      if (retries_ == Retries::kReflection)
        outgoing_.tries = sample_tries::tries(table.white_valid(std::abs(mu), roughness_));
      else if (retries_ == Retries::kInterface)
        outgoing_.tries = sample_tries::tries(table.valid(std::abs(mu), roughness_, mu > 0 ? eta_ : 1 / eta_));
    }
    return outgoing_;
  }
  sample_tries::Tries tries(float mu) const {
    return retries_ == Retries::kNone ? sample_tries::kOneTry : outgoing(mu).tries;
  }
  // single_scattering_albedo(μ_o) for each lane's own index, kept for the last μ_o asked as the one
  // above: the tables read once at each η node the lanes span, for all lanes at once.
  SampledSpectrum<N> lanes_outgoing_albedo(float mu) const {
    if (!(mu == lanes_outgoing_.mu)) {
      lanes_outgoing_.mu = mu;
      const SpecularAlbedo& table = SpecularAlbedo::table();
      if (thin_) {
        lanes_outgoing_.e = SampledSpectrum<N>(table.white(std::abs(mu), roughness_));
      } else {
        std::array<float, N> eta;  // from wo's side
        for (int i = 0; i < N; ++i) eta[i] = mu > 0 ? (*lanes_->eta)[i] : 1 / (*lanes_->eta)[i];
        lanes_outgoing_.e = SampledSpectrum<N>(
            table.interface(SpecularAlbedo::direction(std::abs(mu), roughness_), SpecularAlbedo::Lanes<N>(eta)));
      }
    }
    return lanes_outgoing_.e;
  }

  std::optional<BsdfSample<N>> sample_smooth(const Vec3f& wo, float uc) const {
    const auto F = fresnel(cos_theta(wo));
    const SampledSpectrum<N> Rs = reflected(F);
    const auto t = transmission(wo, F);
    const auto shared = shares(selection(cos_theta(wo)));
    const float R = shared[0], T = t ? shared[1] : 0.f;
    if (R + T <= 0) return std::nullopt;
    if (uc < R / (R + T)) {
      const Vec3f wi(-wo.x, -wo.y, wo.z);
      return BsdfSample<N>{Rs / abs_cos_theta(wi), wi, R / (R + T), true, false, 1.f};
    }
    return BsdfSample<N>{t->weight / abs_cos_theta(t->wi), t->wi, T / (R + T), true, true, t->eta};
  }

  // What the surface reflects and lets through (before the weight `transmission`) from one face's
  // reflectance R, T = 1 − R. A solid interface: R and T. A thin wall is, side by side, a clear
  // sheet (its share t = `transmission`) and the one face over the opaque base (1 − t). The sheet
  // reflects R' = R + (R' − R) and transmits T' = 1 − R'; the opaque share reflects R and passes T
  // into the base (PbrBsdf's diffuse share, weighted 1 − t). So the wall reflects t R' + (1 − t) R
  // and transmits t T', and with the base's (1 − t) T all of it adds to exactly 1: t (R' + T') +
  // (1 − t)(R + T). At t = 1 the full sheet, at t = 0 the single interface (`thin_` is off). (The far
  // side weighted by t (1 − reflected) made a partly clear wall return t (1 − t)(R' − R) more than
  // it received: up to 0.04 near grazing.)
  template <typename S>
  S reflected(const FaceReflectance<S>& F) const {
    return thin_ ? F.R + F.sheet_excess * transmission_ : F.R;
  }
  template <typename S>
  S transmitted(const FaceReflectance<S>& F) const {
    return S(1.f) - (thin_ ? F.R + F.sheet_excess : F.R);
  }
  // R' − R of a lossless sheet whose faces reflect R, shared between s and p polarisation as the
  // bare interface's reflectance `bare` is: Σ ½ R_x (1 − R_x) / (1 + R_x) (R_x' = 2 R_x / (1 + R_x)).
  static float sheet_excess(float R, const FresnelReflectance& bare) {
    const float scale = bare.R > 0 ? R / bare.R : 0.f;
    const auto excess = [](float Rx) { return Rx < 1 ? Rx * (1 - Rx) / (1 + Rx) : 0.f; };
    return bare.R > 0 ? (excess(std::min(1.f, scale * bare.Rs)) + excess(std::min(1.f, scale * bare.Rp))) / 2
                      : excess(R);
  }
  // The reflected and transmitted shares (with the weight) that choose between the two when sampling.
  std::array<float, 2> shares(const FaceReflectance<float>& face) const {
    return {reflected(face), transmission_ * transmitted(face)};
  }

  TrowbridgeReitz distribution_;
  bool smooth_, compensate_;
  SpecularAlbedo::Roughness roughness_;  // where α falls on the albedo tables, when compensating
  float eta_;
  SampledSpectrum<N> tint_;
  bool thin_;
  float transmission_, specular_;
  Retries retries_;
  [[no_unique_address]] OptionalPart<Extensions, SpectralReflectance<N>> lanes_;
  mutable Outgoing outgoing_;  // a cache: safe because a Bsdf is built and used within one thread
  struct LanesOutgoing {
    float mu = std::numeric_limits<float>::quiet_NaN();  // none yet
    SampledSpectrum<N> e;
  };
  [[no_unique_address]] mutable std::conditional_t<Extensions, LanesOutgoing, Absent> lanes_outgoing_;  // a cache too
};

}  // namespace prism
