// Wavelength sampling: the visible pdf is a normalised density that its sampler follows, and
// hero-wavelength estimates of spectral integrals are unbiased, with or without termination.

#include <catch2/catch.hpp>

#include "core/base/rng.h"
#include "core/base/sampler.h"
#include "spectral/cie.h"
#include "spectral/wavelengths.h"
#include "tests/support/chi2.h"

using namespace prism;

TEST_CASE("visible wavelength pdf integrates to 1 over 360-830 nm") {
  double integral = 0;
  const int steps = 470000;
  const double h = (kLambdaMax - kLambdaMin) / steps;
  for (int i = 0; i < steps; ++i) integral += visible_wavelengths_pdf(float(kLambdaMin + (i + 0.5) * h)) * h;
  CHECK(integral == Approx(1.0).epsilon(1e-5));
  CHECK(visible_wavelengths_pdf(359.f) == 0.f);
  CHECK(visible_wavelengths_pdf(831.f) == 0.f);
}

namespace {
float visible_wavelength(float u) {
  float pdf;
  return sample_visible_wavelengths(u, pdf);
}
}  // namespace

TEST_CASE("visible wavelength sampling inverts the pdf's CDF") {
  // Numerically integrated CDF at the sampled wavelength must equal u.
  for (float u : {0.001f, 0.1f, 0.25f, 0.5f, 0.75f, 0.9f, 0.999f}) {
    float pdf = 0;
    const float lambda = sample_visible_wavelengths(u, pdf);
    REQUIRE(lambda >= kLambdaMin);
    REQUIRE(lambda <= kLambdaMax);
    CHECK(pdf == Approx(visible_wavelengths_pdf(lambda)).epsilon(1e-5));  // the pdf returned is p(λ)
    double cdf = 0;
    const int steps = 20000;
    const double h = (lambda - kLambdaMin) / steps;
    for (int i = 0; i < steps; ++i) cdf += visible_wavelengths_pdf(float(kLambdaMin + (i + 0.5) * h)) * h;
    CHECK(cdf == Approx(u).margin(1e-5));
  }
}

// Estimates ∫ȳ dλ from M stratified paths of N hero-rotated wavelengths.
template <int N>
double estimate_y_integral(int paths, WavelengthSampling mode, bool terminate) {
  double sum = 0;
  for (int k = 0; k < paths; ++k) {
    // u.x stratified; u.y cycles the hero through the N strata, so the hero alone is stratified too.
    auto lambda = SampledWavelengths<N>::sample({(k + 0.5f) / paths, (float(k % N) + 0.5f) / N}, mode);
    if (terminate) lambda.terminate_secondary();
    SampledSpectrum<N> y;
    for (int i = 0; i < N; ++i) y[i] = cie().y(lambda[i]);
    sum += safe_div(y, lambda.pdf()).average();
  }
  return sum / paths;
}

TEST_CASE("stratified importance-sampled estimate of the integral of ybar matches the table to 1e-3") {
  const double reference = cie().y_integral;  // Σ ȳ · 1 nm
  CHECK(estimate_y_integral<4>(4096, WavelengthSampling::visible, false) == Approx(reference).epsilon(1e-3));
  CHECK(estimate_y_integral<1>(4096, WavelengthSampling::visible, false) == Approx(reference).epsilon(1e-3));
  CHECK(estimate_y_integral<8>(4096, WavelengthSampling::visible, false) == Approx(reference).epsilon(1e-3));
  CHECK(estimate_y_integral<4>(4096, WavelengthSampling::uniform, false) == Approx(reference).epsilon(1e-3));
}

TEST_CASE("terminating the secondary wavelengths keeps the estimator unbiased") {
  const double reference = cie().y_integral;
  // Only the hero lane remains: the stratification over the N lanes is lost, so use more paths.
  CHECK(estimate_y_integral<4>(1 << 16, WavelengthSampling::visible, true) == Approx(reference).epsilon(1e-3));
  auto lambda = SampledWavelengths<4>::sample({0.2f, 0.3f});
  const float hero_pdf = lambda.pdf()[0];
  lambda.terminate_secondary();
  CHECK(lambda.secondary_terminated());
  CHECK(lambda.pdf()[0] == Approx(hero_pdf / 4));
  for (int i = 1; i < 4; ++i) CHECK(lambda.pdf()[i] == 0.f);
  lambda.terminate_secondary();  // idempotent
  CHECK(lambda.pdf()[0] == Approx(hero_pdf / 4));
}

TEST_CASE("hero wavelengths are stratified: one per 1/N of the CDF, u.y picks the hero") {
  const auto lambda = SampledWavelengths<4>::sample({0.4f, 0.1f});
  CHECK(lambda[0] == Approx(visible_wavelength(0.1f)));
  CHECK(lambda[1] == Approx(visible_wavelength(0.35f)));
  CHECK(lambda[2] == Approx(visible_wavelength(0.6f)));
  CHECK(lambda[3] == Approx(visible_wavelength(0.85f)));
  const auto rotated = SampledWavelengths<4>::sample({0.4f, 0.6f});  // the hero is the third value
  CHECK(rotated[0] == Approx(visible_wavelength(0.6f)));
  CHECK(rotated[1] == Approx(visible_wavelength(0.85f)));
  CHECK(rotated[2] == Approx(visible_wavelength(0.1f)));
}

TEST_CASE("the Sobol sampler stratifies a pixel's M samples of N wavelengths over M x N strata") {
  // The renderer's wavelength dimension (the second 2D request) at a non-power-of-2 count too:
  // M = 24 samples of N = 4 wavelengths hold each of 64 strata of the CDF at most twice, and the
  // first 16 samples each of the 64 exactly once.
  for (const int spp : {16, 24}) {
    Sampler sampler(3, SamplerKind::sobol);
    std::vector<int> strata(64, 0);
    for (int s = 0; s < spp; ++s) {
      sampler.start_pixel_sample({5, 9}, s);
      sampler.get_2d();  // pixel jitter
      const auto lambda = SampledWavelengths<4>::sample(sampler.get_2d(), WavelengthSampling::uniform);
      for (int i = 0; i < 4; ++i) ++strata[int((lambda[i] - kLambdaMin) / (kLambdaMax - kLambdaMin) * 64)];
    }
    for (int k = 0; k < 64; ++k) {
      INFO(spp << " samples, stratum " << k);
      if (spp == 16) REQUIRE(strata[k] == 1);
      REQUIRE(strata[k] >= 1);
      REQUIRE(strata[k] <= 2);
    }
  }
}

TEST_CASE("visible wavelength sampling follows its pdf (chi-square)") {
  constexpr int kBins = 94, kSamples = 500000;  // 5-nm bins
  std::vector<double> observed(kBins, 0);
  Rng rng(13, 0);
  for (int i = 0; i < kSamples; ++i) {
    const float l = visible_wavelength(rng.uniform());
    observed[std::min(kBins - 1, int((l - kLambdaMin) / (kLambdaMax - kLambdaMin) * kBins))] += 1;
  }
  double statistic = 0;
  for (int b = 0; b < kBins; ++b) {
    double p = 0;  // ∫ pdf over the bin, midpoint rule at 0.05 nm
    const double lo = kLambdaMin + b * 5.0;
    for (int k = 0; k < 100; ++k) p += visible_wavelengths_pdf(float(lo + (k + 0.5) * 0.05)) * 0.05;
    const double expected = p * kSamples;
    statistic += sqr(observed[b] - expected) / expected;
  }
  const double p_value = 1 - test::regularized_gamma_p((kBins - 1) / 2.0, statistic / 2);
  INFO("chi2 " << statistic << " for " << kBins - 1 << " degrees of freedom, p " << p_value);
  CHECK(p_value > 1e-3);
}

TEST_CASE("wavelengths at the ends of the range are valid everywhere") {
  for (const float u : {0.f, 0x1p-24f, 0.5f, 1.f - 0x1p-24f}) {
    const auto lambda = SampledWavelengths<4>::sample({u, u});
    for (int i = 0; i < 4; ++i) {
      REQUIRE(lambda[i] >= kLambdaMin);
      REQUIRE(lambda[i] <= kLambdaMax);
      REQUIRE(lambda.pdf()[i] > 0);
      REQUIRE(std::isfinite(lambda.pdf()[i]));
    }
  }
  CHECK(visible_wavelength(0.f) == kLambdaMin);
  CHECK(visible_wavelength(1.f) == kLambdaMax);
  for (const float l : {kLambdaMin, kLambdaMax}) {
    CHECK(std::isfinite(cie().x(l)));
    CHECK(cie().d65(l) > 0);
    CHECK(evaluate(RgbAlbedoSpectrum(Rgb{0.2f, 0.9f, 0.1f}), l) >= 0);
    CHECK(std::isfinite(evaluate(RgbIlluminantSpectrum(Rgb{5, 1, 0}), l)));
  }
}

TEST_CASE("sampled_xyz_mean is the mean of to_xyz over the path's wavelengths") {
  // What the renderer gives a camera ray that sees a constant sky at once (sky_xyz): it must be the
  // mean of the estimate it replaces, here from 2^16 stratified paths of 8 hero-rotated wavelengths.
  for (const Rgb rgb : {Rgb{0.5f, 0.5f, 0.5f}, Rgb{0.9f, 0.2f, 0.05f}}) {
    const Spectrum sky = RgbIlluminantSpectrum(rgb);
    constexpr int kPaths = 1 << 16;
    double sum[3] = {0, 0, 0};
    for (int k = 0; k < kPaths; ++k) {
      const auto lambda = SampledWavelengths<8>::sample({(k + 0.5f) / kPaths, (float(k % 8) + 0.5f) / 8});
      const Xyz xyz = to_xyz(sample(sky, lambda), lambda);
      sum[0] += xyz.x, sum[1] += xyz.y, sum[2] += xyz.z;
    }
    const Xyz mean = sampled_xyz_mean(sky);
    CHECK(mean.x == Approx(sum[0] / kPaths).epsilon(1e-5));
    CHECK(mean.y == Approx(sum[1] / kPaths).epsilon(1e-5));
    CHECK(mean.z == Approx(sum[2] / kPaths).epsilon(1e-5));
  }
}
