#pragma once
// Pearson's χ² goodness-of-fit test of a direction sampler against its claimed pdf (the method
// of Mitsuba's test suite; Jakob 2010). The sphere is divided into cells in polar coordinates
// (θ', φ') about an axis: the direction of highest density among the first samples, with cells
// uniform in (θ'/π)^(1/3), so that even the narrowest GGX lobes are resolved.

#include <functional>
#include <optional>

#include "core/base/vec.h"

namespace prism::test {

struct Chi2Result {
  double statistic, p_value;
  int degrees_of_freedom;
  bool passed;  // p ≥ significance
};

// sample(u1, u2, u3) returns a unit direction or nothing (a failed or excluded sample); pdf(w)
// the density of the returned directions (it may integrate to less than 1). Expected counts
// come from integrating pdf over each cell (composite Simpson). Under the sanitizers it draws a
// quarter of the samples (sanitizers.h).
Chi2Result chi2_test(const std::function<std::optional<Vec3f>(float, float, float)>& sample,
                     const std::function<double(const Vec3f&)>& pdf, int samples = 200000, int theta_bins = 48,
                     int phi_bins = 32, double significance = 1e-3, uint64_t seed = 1);

// Regularised lower incomplete gamma P(a, x) (series for x < a + 1, else continued fraction;
// Numerical Recipes §6.2), for the χ² distribution's CDF.
double regularized_gamma_p(double a, double x);

}  // namespace prism::test
