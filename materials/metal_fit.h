#pragma once
// A metal's complex index n + ik from the colour glTF gives it (its normal-incidence reflectance),
// for metals without measured n, k: Gulbrandsen's parametrisation, with the edge tint chosen so
// that the exact conductor Fresnel reflects as much light in total as glTF's reference Schlick
// metal. Measured metals (the catalogue) never come through here.

#include <array>
#include <cmath>

#include "core/base/math.h"
#include "spectral/sampled_spectrum.h"

namespace prism {

// Gulbrandsen's metal (2014, "Artist Friendly Metallic Fresnel", JCGT 3(4)) of normal-incidence
// reflectance r < 1 and edge tint g ∈ [0, 1]: n blended between (1 − r)/(1 + r) and
// (1 + √r)/(1 − √r) by g, and the k that gives F0 = r, k² = (r (n + 1)² − (n − 1)²) / (1 − r).
inline std::array<float, 2> gulbrandsen_nk(float r, float g) {
  const float sr = std::sqrt(r);
  const float n = g * (1 - r) / (1 + r) + (1 - g) * (1 + sr) / (1 - sr);
  return {n, std::sqrt(std::max((r * sqr(n + 1) - sqr(n - 1)) / (1 - r), 0.f))};
}

// The edge tints g(r) with which Gulbrandsen's metal of reflectance r reflects as much light in
// total as glTF's reference metal (Schlick, F0 = r), at r = 0, 0.01, …, 1 (built on first use).
const std::array<float, 101>& schlick_matched_edge_tints();

// Each lane's n, k of a metal whose normal-incidence reflectance is r_λ: Gulbrandsen's, with the
// edge tint that gives the directional albedo of glTF's reference metal. Measured metals in the
// visible sit close to it (edge tints 0.9-1 for Cu, Al, Ag, Au); the Fresnel formula stays exact.
// Two loops over the lanes, each run on all lanes at once (vector code): in one, GCC turns the
// clamp's constant ends into branches and leaves the lanes one by one.
template <int N>
struct MetalIndex {
  SampledSpectrum<N> n, k;
};
template <int N>
MetalIndex<N> metal_nk_from_reflectance(const SampledSpectrum<N>& reflectance) {
  const std::array<float, 101>& tint = schlick_matched_edge_tints();
  std::array<float, N> r;
  // r < 1 keeps k finite; NaN becomes 0 (std::max(0, NaN) is 0), so the table is never read outside.
  for (int i = 0; i < N; ++i) r[i] = std::max(0.f, std::min(reflectance[i], 0.999f));
  MetalIndex<N> m;
  for (int i = 0; i < N; ++i) {
    const float x = r[i] * 100;
    const int j = int(x);  // ≤ 99
    const auto nk = gulbrandsen_nk(r[i], tint[j] + (x - float(j)) * (tint[j + 1] - tint[j]));
    m.n[i] = nk[0], m.k[i] = nk[1];
  }
  return m;
}

}  // namespace prism
