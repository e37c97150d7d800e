// Piecewise-constant distributions: densities that integrate to 1, samples that land in each
// bucket as often as its share of the function says, and never in a bucket where it is zero.

#include <catch2/catch.hpp>

#include "core/base/distribution.h"
#include "core/base/rng.h"

using namespace prism;

TEST_CASE("1D piecewise-constant sampling follows the function and skips its zeros") {
  const std::vector<float> f = {0, 1, 3, 0, 4, 0};
  const PiecewiseConstant1D d(f);
  CHECK(d.integral() == Approx(8.0 / 6));
  std::vector<int> counts(f.size(), 0);
  Rng rng(3, 0);
  constexpr int kSamples = 100000;
  for (int i = 0; i < kSamples; ++i) {
    const auto s = d.sample(rng.uniform());
    REQUIRE(s.bucket == std::min(int(s.x * 6), 5));
    REQUIRE(s.pdf == Approx(f[s.bucket] / d.integral()));
    ++counts[s.bucket];
  }
  for (size_t i = 0; i < f.size(); ++i) {
    const double p = f[i] / 8.0, sigma = std::sqrt(kSamples * p * (1 - p));
    INFO("bucket " << i);
    CHECK(std::abs(counts[i] - kSamples * p) <= 5 * sigma);
  }
  // The ends of [0, 1) fall in the first and last non-zero buckets.
  CHECK(d.sample(0.f).bucket == 1);
  CHECK(d.sample(0x1.fffffep-1f).bucket == 4);
  CHECK(d.sample(0x1.fffffep-1f).x < 1.f);

  const PiecewiseConstant1D zero(std::vector<float>{0, 0, 0, 0});
  CHECK(zero.sample(0.6f).bucket == 2);  // uniform
  CHECK(zero.pdf(1) == 1.f);
}

TEST_CASE("2D piecewise-constant sampling: pdf matches the samples and integrates to 1") {
  constexpr int nu = 5, nv = 4;
  std::vector<float> f(nu * nv);
  Rng rng(5, 0);
  for (float& v : f) v = rng.uniform() < 0.3f ? 0.f : rng.uniform() * 10;
  for (int u = 0; u < nu; ++u) f[2 * nu + u] = 0;  // an empty row
  double total = 0;
  for (float v : f) total += v;
  const PiecewiseConstant2D d(f, nu, nv);

  double integral = 0;
  for (int v = 0; v < nv; ++v)
    for (int u = 0; u < nu; ++u) integral += d.pdf({(u + 0.5f) / nu, (v + 0.5f) / nv}) / (nu * nv);
  CHECK(integral == Approx(1).epsilon(1e-5));

  std::vector<int> counts(f.size(), 0);
  constexpr int kSamples = 200000;
  for (int i = 0; i < kSamples; ++i) {
    const auto s = d.sample({rng.uniform(), rng.uniform()});
    REQUIRE(s.pdf == Approx(d.pdf(s.p)).epsilon(1e-5));
    ++counts[std::min(int(s.p.y * nv), nv - 1) * nu + std::min(int(s.p.x * nu), nu - 1)];
  }
  for (size_t i = 0; i < f.size(); ++i) {
    const double p = f[i] / total, sigma = std::sqrt(kSamples * p * (1 - p));
    INFO("cell " << i);
    if (f[i] == 0)
      CHECK(counts[i] == 0);
    else
      CHECK(std::abs(counts[i] - kSamples * p) <= 5 * sigma);
  }
}
