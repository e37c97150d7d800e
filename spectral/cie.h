#pragma once
// CIE 1931 2° colour-matching functions and illuminant D65 (data/cie/), and the conversion of
// spectra to XYZ. Convention: XYZ = ∫ S(λ) {x̄, ȳ, z̄}(λ) dλ / ∫ ȳ(λ) dλ, so that an illuminant of
// luminance 1 (e.g. the normalised D65 below) has Y = 1 and a perfect white under it has Y = 1.

#include <algorithm>
#include <array>
#include <bit>
#include <vector>

#include "spectral/rgb.h"
#include "spectral/spectrum.h"

namespace prism {

struct CieTables {
  DenselySampledSpectrum x, y, z;
  DenselySampledSpectrum d65;  // scaled so that its XYZ has Y = 1
  float y_integral;            // Σ ȳ(λ) · 1 nm over 360–830 nm
  // x̄, ȳ, z̄ (and a 0) side by side, one row per nm from kLambdaMin: the renderer reads all three
  // at every wavelength of every sample, one 4-float load per row.
  struct alignas(16) XyzRow {
    float v[4];
  };
  std::vector<XyzRow> xyz_rows;
};

// Loaded from data/cie/ on first use (thread-safe); throws prism::Error if the files are absent.
const CieTables& cie();

// ∫ S {x̄,ȳ,z̄} dλ / ∫ȳ dλ by 1-nm sums over 360–830 nm.
Xyz spectrum_to_xyz(const Spectrum& s);

// The mean of to_xyz over the wavelengths a path samples, for a spectrum S: ∫ S {x̄,ȳ,z̄} dλ / ∫ȳ
// with the tables linear between their 1-nm rows as to_xyz reads them, by Simpson's rule on each
// nm (exact where S is linear there, as the CIE tables and D65 are).
Xyz sampled_xyz_mean(const Spectrum& s);

// Monte Carlo estimate of the same integral from one path's N wavelengths: the average over
// lanes of S(λᵢ) x̄(λᵢ) / p(λᵢ), divided by ∫ȳ. Terminated lanes (pdf 0) contribute 0.
template <int N>
Xyz to_xyz(const SampledSpectrum<N>& s, const SampledWavelengths<N>& lambda) {
  using Float4 = float __attribute__((vector_size(16)));
  const CieTables& t = cie();
  // Each lane's row and fraction (locate_rows), then its weight S(λ)/p(λ), all lanes at once
  // (SIMD): a lane outside the rows or terminated (pdf 0) weighs 0, whatever its S (a terminated
  // lane's may be anything). (Written so that the loop vectorises on AVX2 too: no branches or
  // selects of a quotient, the division done on every lane, by at least 1e-30.)
  const RowPlaces<N> p = locate_rows(lambda, kLambdaMin, int(t.xyz_rows.size()));
  std::array<float, N> w;
  for (int i = 0; i < N; ++i) {
    const float pdf = lambda.pdf()[i];
    const bool keep = (p.inside[i] > 0.f) & (pdf > 0.f);
    w[i] = (keep ? s[i] : 0.f) / std::max(pdf, 1e-30f);
  }
  // Then x̄, ȳ, z̄ linear between the 1-nm rows, one 4-float row pair per lane.
  Float4 sum{0, 0, 0, 0};
  for (int i = 0; i < N; ++i) {
    const auto a = std::bit_cast<Float4>(t.xyz_rows[p.row[i]]), b = std::bit_cast<Float4>(t.xyz_rows[p.row[i] + 1]);
    sum += w[i] * ((1.f - p.fraction[i]) * a + p.fraction[i] * b);
  }
  const float norm = 1.f / (N * t.y_integral);
  return {sum[0] * norm, sum[1] * norm, sum[2] * norm};
}

}  // namespace prism
