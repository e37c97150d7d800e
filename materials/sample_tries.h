#pragma once
// Sampling a compensated microfacet lobe again where a visible normal sends wo to the wrong side.
// Such a sample is the light that single scattering loses, and carries nothing; the multiple-
// scattering compensation (Turquin 2019) scales up the samples that succeed, so each failure costs
// variance, and inside rough glass it compounds from bounce to bounce. Up to kTries tries, each
// succeeding with probability P(μ_o) (SpecularAlbedo::valid, white_valid), find a direction with
// the density of one try times
//   (1 − (1 − P)^kTries) / P        (a geometric series over the tries that fail first),
// which the lobe's pdf reports, so that MIS stays consistent with the sampling. P is tabulated for
// isotropic lobes, to about 10⁻³, and a sample's weight carries that error as the compensation
// carries E's: a lobe retries only where more than 1% of its tries fail, so that a nearly smooth
// one, whose gain would be nothing, keeps its exact single try.

#include <algorithm>
#include <bit>
#include <cstdint>

#include "core/base/rng.h"
#include "core/base/vec.h"

namespace prism::sample_tries {

constexpr int kTries = 8;

// How many tries a lobe whose tries succeed with probability P takes, and the pdf of those tries
// over one try's.
struct Tries {
  int count;
  float pdf_scale;
};
inline Tries tries(float P) {
  if (!(P < 0.99f)) return {1, 1.f};
  P = std::max(P, 1e-3f);
  const float q = 1 - P, q2 = q * q, q4 = q2 * q2;
  static_assert(kTries == 8);
  return {kTries, (1 - q4 * q4) / P};
}
inline constexpr Tries kOneTry{1, 1.f};

// The next try's numbers: a hash of the failed try's (uniform and independent of them).
inline void next(float& uc, Vec2f& u) {
  const uint64_t h = hash_ints(std::bit_cast<uint32_t>(u.x), std::bit_cast<uint32_t>(u.y), std::bit_cast<uint32_t>(uc));
  u = {float(h >> 40) * 0x1p-24f, float((h >> 16) & 0xffffff) * 0x1p-24f};
  uc = float(mix_bits(h) >> 40) * 0x1p-24f;
}

}  // namespace prism::sample_tries
