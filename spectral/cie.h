#pragma once
// CIE 1931 2° colour-matching functions and illuminant D65 (data/cie/), and the conversion of
// spectra to XYZ. Convention: XYZ = ∫ S(λ) {x̄, ȳ, z̄}(λ) dλ / ∫ ȳ(λ) dλ, so that an illuminant of
// luminance 1 (e.g. the normalised D65 below) has Y = 1 and a perfect white under it has Y = 1.

#include "spectral/rgb.h"
#include "spectral/spectrum.h"

namespace prism {

struct CieTables {
  DenselySampledSpectrum x, y, z;
  DenselySampledSpectrum d65;  // scaled so that its XYZ has Y = 1
  float y_integral;            // Σ ȳ(λ) · 1 nm over 360–830 nm
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
    x[i] = t.x(lambda[i]);
    y[i] = t.y(lambda[i]);
    z[i] = t.z(lambda[i]);
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
