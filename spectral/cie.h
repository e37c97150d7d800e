#pragma once
// CIE 1931 2° colour-matching functions and illuminant D65 (data/cie/), and the conversion of
// spectra to XYZ. Convention: XYZ = ∫ S(λ) {x̄, ȳ, z̄}(λ) dλ / ∫ ȳ(λ) dλ, so that an illuminant of
// luminance 1 (e.g. the normalised D65 below) has Y = 1 and a perfect white under it has Y = 1.

#include <array>
#include <vector>

#include "spectral/rgb.h"
#include "spectral/spectrum.h"

namespace prism {

struct CieTables {
  DenselySampledSpectrum x, y, z;
  DenselySampledSpectrum d65;                  // scaled so that its XYZ has Y = 1
  float y_integral;                            // Σ ȳ(λ) · 1 nm over 360–830 nm
  std::vector<std::array<float, 3>> xyz_rows;  // x̄, ȳ, z̄ side by side, one row per nm

  // x̄(λ), ȳ(λ), z̄(λ) as x, y and z return them (linear between the 1-nm rows, 0 outside), found
  // with one index: the renderer asks for all three at every wavelength of every sample.
  std::array<float, 3> xyz_bar(float lambda) const {
    const float u = lambda - kLambdaMin;
    const int last = int(xyz_rows.size()) - 1;
    if (!(u >= 0.f) || u > float(last)) return {0, 0, 0};
    const int i = std::min(int(u), last - 1);
    const float t = u - float(i);
    const auto &a = xyz_rows[i], &b = xyz_rows[i + 1];
    return {(1.f - t) * a[0] + t * b[0], (1.f - t) * a[1] + t * b[1], (1.f - t) * a[2] + t * b[2]};
  }
};

// Loaded from data/cie/ on first use (thread-safe); throws prism::Error if the files are absent.
const CieTables& cie();

// ∫ S {x̄,ȳ,z̄} dλ / ∫ȳ dλ by 1-nm sums over 360–830 nm.
Xyz spectrum_to_xyz(const Spectrum& s);

// Monte Carlo estimate of the same integral from one path's N wavelengths: the average over
// lanes of S(λᵢ) x̄(λᵢ) / p(λᵢ), divided by ∫ȳ. Terminated lanes (pdf 0) contribute 0.
template <int N>
Xyz to_xyz(const SampledSpectrum<N>& s, const SampledWavelengths<N>& lambda) {
  const CieTables& t = cie();
  SampledSpectrum<N> x, y, z;
  for (int i = 0; i < N; ++i) {
    const auto bar = t.xyz_bar(lambda[i]);
    x[i] = bar[0], y[i] = bar[1], z[i] = bar[2];
  }
  const SampledSpectrum<N> w = safe_div(s, lambda.pdf());
  const float norm = 1.f / (N * t.y_integral);
  float sx = 0, sy = 0, sz = 0;
  for (int i = 0; i < N; ++i) {
    sx += w[i] * x[i];
    sy += w[i] * y[i];
    sz += w[i] * z[i];
  }
  return {sx * norm, sy * norm, sz * norm};
}

}  // namespace prism
