#pragma once
// What every BSDF lobe returns from sampling, and the shading-space conventions they share:
// directions are unit vectors in the local shading frame, z = shading normal, wo points away
// from the surface towards the viewer, wi towards the light.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <type_traits>

#include "core/base/vec.h"
#include "spectral/sampled_spectrum.h"

namespace prism {

template <int N>
struct BsdfSample {
  SampledSpectrum<N> f;  // BSDF value for (wo, wi)
  Vec3f wi;
  float pdf = 0;          // solid-angle density; for a delta lobe, the discrete probability
  bool specular = false;  // delta lobe: pdf is a probability, f includes the delta
  bool transmission = false;
  float eta = 1;  // relative index crossed by a refraction (1 otherwise)
};

// A BSDF's value and sampling density at one pair of directions, computed together where they
// share their work (a half vector, a Fresnel reflectance).
template <int N>
struct BsdfEval {
  SampledSpectrum<N> f;
  float pdf;
};

// A lobe's f and pdf together: its own eval where it shares their work, else the two calls.
template <int N, class Lobe>
BsdfEval<N> lobe_eval(const Lobe& lobe, const Vec3f& wo, const Vec3f& wi) {
  if constexpr (requires { lobe.eval(wo, wi); })
    return lobe.eval(wo, wi);
  else
    return BsdfEval<N>{lobe.f(wo, wi), lobe.pdf(wo, wi)};
}

// A mixture's choice of lobe by u.x: the lobe of probability `width` owns u.x ∈ [lo, lo + width),
// and gets u.x rescaled to [0, 1) for its own sample (as Cycles 3 does), so that the points of a
// stratified pattern that choose a lobe still cover its square evenly (a separate choice number
// would send it a random subset of them).
inline float within_lobe(float u, float lo, float width) {
  return width > 0 ? std::clamp((u - lo) / width, 0.f, 0.99999994f) : 0.f;
}

// The end of a mixture's sample_f: a non-delta sample of one of its lobes takes the whole
// mixture's f and pdf towards its direction (the mixture as eval finds it), or is dropped where
// that pdf is 0. Every lobe's sample_f returns its own s in place (NRVO), so s is changed there.
template <int N>
void take_mixture(std::optional<BsdfSample<N>>& s, const BsdfEval<N>& mixture) {
  if (!(mixture.pdf > 0)) {
    s.reset();
    return;
  }
  s->f = mixture.f;
  s->pdf = mixture.pdf;
}

// One delta direction of a BSDF and the share of light it carries (f·|cos θ_i| with the delta
// integrated out), for tracers that follow every specular branch.
template <int N>
struct DeltaLobe {
  Vec3f wi;
  SampledSpectrum<N> weight;
  bool transmission;
  float eta;  // relative index crossed (1 for reflection)
};

template <int N>
struct DeltaLobes {
  std::array<DeltaLobe<N>, 4> lobes;  // a coat, a metal, a dielectric's reflection and transmission
  int count = 0;

  void add(const DeltaLobe<N>& l) {
    if (!l.weight.is_zero()) lobes[count++] = l;
  }
  void add_scaled(const DeltaLobes& other, float s) {
    for (int i = 0; i < other.count; ++i)
      add({other.lobes[i].wi, other.lobes[i].weight * s, other.lobes[i].transmission, other.lobes[i].eta});
  }
  const DeltaLobe<N>* begin() const { return lobes.data(); }
  const DeltaLobe<N>* end() const { return lobes.data() + count; }
};

// What a lobe compiled without an optional part holds in its place (with [[no_unique_address]],
// nothing): the glTF extensions' parts are compiled only into the lobes of materials that use them.
struct Absent {
  constexpr Absent() = default;
  template <typename T>
  constexpr Absent(const T&) {}
};
template <bool Present, typename T>
using OptionalPart = std::conditional_t<Present, std::optional<T>, Absent>;

inline float cos_theta(const Vec3f& w) { return w.z; }
inline float abs_cos_theta(const Vec3f& w) { return std::abs(w.z); }
inline bool same_hemisphere(const Vec3f& a, const Vec3f& b) { return a.z * b.z > 0; }

}  // namespace prism
