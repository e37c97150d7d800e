#pragma once
// What every BSDF lobe returns from sampling, and the shading-space conventions they share:
// directions are unit vectors in the local shading frame, z = shading normal, wo points away
// from the surface towards the viewer, wi towards the light.

#include <cmath>

#include "base/vec.h"
#include "spectral/sampled_spectrum.h"

namespace prism {

template <int N>
struct BsdfSample {
  SampledSpectrum<N> f;        // BSDF value for (wo, wi)
  Vec3f wi;
  float pdf = 0;               // solid-angle density; for a delta lobe, the discrete probability
  bool specular = false;       // delta lobe: pdf is a probability, f includes the delta
  bool transmission = false;
  float eta = 1;               // relative index crossed by a refraction (1 otherwise)
};

inline float cos_theta(const Vec3f& w) { return w.z; }
inline float abs_cos_theta(const Vec3f& w) { return std::abs(w.z); }
inline bool same_hemisphere(const Vec3f& a, const Vec3f& b) { return a.z * b.z > 0; }

}  // namespace prism
