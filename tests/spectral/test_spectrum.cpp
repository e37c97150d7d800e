// Spectra at a path's wavelengths: where a kind has its own all-lanes form, it gives each lane
// exactly what the kind gives that wavelength alone.

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/base/rng.h"
#include "spectral/spectrum.h"

using namespace prism;

TEST_CASE("a dense spectrum at a path's wavelengths equals its value at each, 0 outside its span") {
  // 400-700 nm, so that uniformly sampled wavelengths (360-830 nm) also fall below and above it.
  std::vector<float> values(301);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 1.f + std::sin(0.05f * float(i));
  const DenselySampledSpectrum dense(400, values);
  const Spectrum spectrum = dense;
  Rng rng(7, 0);
  int outside = 0;
  for (int k = 0; k < 2000; ++k) {
    const auto lambda = SampledWavelengths<8>::sample({rng.uniform(), rng.uniform()}, WavelengthSampling::uniform);
    const SampledSpectrum<8> lanes = sample(spectrum, lambda);
    for (int i = 0; i < 8; ++i) {
      CHECK(lanes[i] == dense(lambda[i]));
      outside += lambda[i] < 400.f || lambda[i] > 700.f;
    }
  }
  CHECK(outside > 1000);  // the span's ends were exercised
  CHECK(dense(399.5f) == 0.f);
  CHECK(dense(700.5f) == 0.f);
  CHECK(dense(700.f) == values.back());
}
