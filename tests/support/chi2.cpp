#include "tests/support/chi2.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/base/frame.h"
#include "core/base/rng.h"
#include "tests/support/sanitizers.h"

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
  samples = sanitized_samples(samples);
  Rng rng(seed, 0);
  std::vector<Vec3f> directions;
  for (int i = 0; i < samples; ++i) {
    const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    if (const auto w = sample(u1, u2, u3)) directions.push_back(*w);
  }
  // The axis: the densest of the first sampled directions (any axis gives a valid test; this one
  // puts the finest cells where the density peaks).
  Vec3f axis(0, 0, 1);
  double best = -1;
  for (size_t i = 0; i < std::min<size_t>(directions.size(), 2000); ++i)
    if (const double p = pdf(directions[i]); p > best) best = p, axis = directions[i];
  const Frame frame = Frame::from_z(normalize(axis));
  // Cell coordinates: t = (θ'/π)^(1/3) ∈ [0, 1], φ' ∈ [0, 2π).
  const auto direction_at = [&](double t, double phi) {
    const double theta = kPi * t * t * t;
    return frame.to_world(
        Vec3f(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)), float(std::cos(theta))));
  };
  const auto cell_of = [&](const Vec3f& w) {
    const Vec3f l = frame.to_local(w);
    // atan2 of sin and cos: acos(cos θ') would lose small angles to float rounding near 1.
    const double theta = std::atan2(std::hypot(double(l.x), double(l.y)), double(l.z));
    const int t = std::clamp(int(std::cbrt(theta / kPi) * theta_bins), 0, theta_bins - 1);
    double phi = std::atan2(double(l.y), double(l.x));
    if (phi < 0) phi += 2 * kPi;
    const int p = std::clamp(int(phi / (2 * kPi) * phi_bins), 0, phi_bins - 1);
    return t * phi_bins + p;
  };
  std::vector<double> observed(size_t(theta_bins) * phi_bins, 0), expected(observed.size(), 0);
  for (const Vec3f& w : directions) observed[cell_of(w)] += 1;
  // ∫ pdf dω over each cell, dω = sin θ' dθ' dφ' with dθ' = 3π t² dt, by a 2D composite Simpson
  // rule: 8 × 8 intervals per cell, or 64 × 64 where the pdf drops to zero inside the cell
  // (a horizon), so that the jump costs no accuracy.
  const auto cell_integral = [&](int t, int p, int sub) {
    const double t0 = double(t) / theta_bins, dt = 1.0 / theta_bins / sub;
    const double phi0 = 2 * kPi * p / phi_bins, dphi = 2 * kPi / phi_bins / sub;
    double integral = 0;
    bool zero = false, nonzero = false;
    for (int i = 0; i <= sub; ++i)
      for (int j = 0; j <= sub; ++j) {
        const double tt = t0 + i * dt, phi = phi0 + j * dphi;
        const double jacobian = std::sin(kPi * tt * tt * tt) * 3 * kPi * tt * tt;
        const double wi = (i == 0 || i == sub) ? 1 : (i % 2 ? 4 : 2);
        const double wj = (j == 0 || j == sub) ? 1 : (j % 2 ? 4 : 2);
        const double value = pdf(direction_at(tt, phi));
        (value > 0 ? nonzero : zero) = true;
        integral += wi * wj * value * jacobian;
      }
    return std::pair{integral * dt * dphi / 9, zero && nonzero};
  };
  for (int t = 0; t < theta_bins; ++t)
    for (int p = 0; p < phi_bins; ++p) {
      auto [integral, straddles] = cell_integral(t, p, 8);
      if (straddles) integral = cell_integral(t, p, 64).first;
      expected[t * phi_bins + p] = integral * samples;
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
    statistic += sqr(observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pooled_exp > 0) {
    statistic += sqr(pooled_obs - pooled_exp) / pooled_exp;
    ++cells;
  } else if (pooled_obs > 0) {
    return {INFINITY, 0, cells, false};  // samples where the pdf says there are none
  }
  const int dof = std::max(cells - 1, 1);
  const double p_value = 1 - regularized_gamma_p(dof / 2.0, statistic / 2);
  return {statistic, p_value, dof, p_value >= significance};
}

}  // namespace prism::test
