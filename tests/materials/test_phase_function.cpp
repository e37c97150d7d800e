// The Henyey–Greenstein phase function (materials/phase_function.h): a density on the sphere
// whose mean cosine is g, sampled exactly (χ²), with eval, pdf and sample agreeing.

#include <catch2/catch.hpp>
#include <cmath>

#include "materials/phase_function.h"
#include "tests/support/chi2.h"

using namespace prism;

TEST_CASE("Henyey-Greenstein: a density whose mean cosine is g, for every g") {
  for (const float g : {-0.9f, -0.4f, 0.f, 0.0005f, 0.3f, 0.7f, 0.95f}) {
    INFO("g " << g);
    const HenyeyGreenstein hg{g};
    // ∫ p dω and ∫ cos θ p dω by the midpoint rule in cos θ (2π about the axis).
    double total = 0, mean_cos = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double mu = -1 + (i + 0.5) * 2.0 / n;
      const double p = hg.density(float(mu)) * 2 * kPi * 2.0 / n;
      total += p;
      mean_cos += mu * p;
    }
    CHECK(total == Approx(1).epsilon(1e-3));
    CHECK(mean_cos == Approx(g).margin(1e-3));
    // The inverse CDF runs from backwards (u = 0) to forwards (u = 1).
    CHECK(hg.inverse_cdf(0.f) == Approx(-1).margin(1e-5));
    CHECK(hg.inverse_cdf(1.f) == Approx(1).margin(1e-5));
  }
}

TEST_CASE("Henyey-Greenstein sampling: chi-square against its pdf, eval equal to pdf") {
  const Vec3f d = normalize(Vec3f(0.3f, -0.5f, 0.8f));
  for (const float g : {-0.7f, 0.f, 0.5f, 0.9f}) {
    INFO("g " << g);
    const HenyeyGreenstein hg{g};
    const auto result = test::chi2_test(
        [&](float u1, float u2, float) {
          return std::optional(hg.sample(d, {u1, u2}));
        },
        [&](const Vec3f& w) { return double(hg.pdf(d, w)); });
    INFO("chi2 " << result.statistic << " dof " << result.degrees_of_freedom << " p " << result.p_value);
    CHECK(result.passed);
    for (const Vec3f w : {d, -d, normalize(Vec3f(1, 2, 3))}) {
      CHECK(hg.eval(d, w) == hg.pdf(d, w));
      CHECK(length(hg.sample(d, {0.37f, 0.81f})) == Approx(1).epsilon(1e-5));
    }
  }
  // The test can fail: samples with g's sign turned do not have g's density.
  const HenyeyGreenstein forwards{0.5f}, backwards{-0.5f};
  CHECK_FALSE(test::chi2_test(
                  [&](float u1, float u2, float) {
                    return std::optional(backwards.sample(d, {u1, u2}));
                  },
                  [&](const Vec3f& w) { return double(forwards.pdf(d, w)); })
                  .passed);
}
