#include "support/chi2.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/rng.h"

namespace prism::test {

double regularized_gamma_p(double a, double x) {
  if (x <= 0) return 0;
  const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1) {  // Σ xⁿ / (a (a+1) ... (a+n))
    double term = 1 / a, sum = term;
    for (int n = 1; n < 1000 && std::abs(term) > 1e-15 * std::abs(sum); ++n) sum += term *= x / (a + n);
    return sum * std::exp(log_prefix);
  }
  // Lentz's method for the continued fraction of Q(a, x).
  double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    h *= d * c;
    if (std::abs(d * c - 1) < 1e-15) break;
  }
  return 1 - std::exp(log_prefix) * h;
}

Chi2Result chi2_test(const std::function<std::optional<Vec3f>(float, float, float)>& sample,
                     const std::function<double(const Vec3f&)>& pdf, int samples, int theta_bins, int phi_bins,
                     double significance, uint64_t seed) {
  const auto cell_of = [&](const Vec3f& w) {
    const int t = std::clamp(int((w.z + 1) / 2 * theta_bins), 0, theta_bins - 1);
    double phi = std::atan2(double(w.y), double(w.x));
    if (phi < 0) phi += 2 * kPi;
    const int p = std::clamp(int(phi / (2 * kPi) * phi_bins), 0, phi_bins - 1);
    return t * phi_bins + p;
  };
  std::vector<double> observed(size_t(theta_bins) * phi_bins, 0), expected(observed.size(), 0);
  Rng rng(seed, 0);
  for (int i = 0; i < samples; ++i) {
    const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    if (const auto w = sample(u1, u2, u3)) observed[cell_of(*w)] += 1;
  }
  // ∫ pdf dω over each cell, dω = dcos θ dφ, by a 2D composite Simpson rule (8×8 intervals).
  constexpr int kSub = 8;
  for (int t = 0; t < theta_bins; ++t)
    for (int p = 0; p < phi_bins; ++p) {
      const double z0 = -1 + 2.0 * t / theta_bins, dz = 2.0 / theta_bins / kSub;
      const double phi0 = 2 * kPi * p / phi_bins, dphi = 2 * kPi / phi_bins / kSub;
      double integral = 0;
      for (int i = 0; i <= kSub; ++i)
        for (int j = 0; j <= kSub; ++j) {
          const double z = z0 + i * dz, phi = phi0 + j * dphi, r = std::sqrt(std::max(0.0, 1 - z * z));
          const double wi = (i == 0 || i == kSub) ? 1 : (i % 2 ? 4 : 2);
          const double wj = (j == 0 || j == kSub) ? 1 : (j % 2 ? 4 : 2);
          integral += wi * wj * pdf(Vec3f(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
        }
      expected[t * phi_bins + p] = integral * dz * dphi / 9 * samples;
    }
  // Cells expecting fewer than 5 samples are pooled into one (Pearson's rule of thumb).
  double statistic = 0, pooled_obs = 0, pooled_exp = 0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5) {
      pooled_obs += observed[i];
      pooled_exp += expected[i];
      continue;
    }
    statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pooled_exp > 0) {
    statistic += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++cells;
  } else if (pooled_obs > 0) {
    return {INFINITY, 0, cells, false};  // samples where the pdf says there are none
  }
  const int dof = cells - 1;
  const double p_value = 1 - regularized_gamma_p(dof / 2.0, statistic / 2);
  return {statistic, p_value, dof, p_value >= significance};
}

}  // namespace prism::test
