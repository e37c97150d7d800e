#include "materials/metal_fit.h"

#include <algorithm>

#include "materials/fresnel.h"

namespace prism {

namespace {

// Directional albedo difference ∫ (F_exact − F_Schlick) 2cos θ dcos θ (64-point midpoint rule).
double albedo_difference(double r, double g) {
  const auto [n, k] = gulbrandsen_nk(float(r), float(g));
  double sum = 0;
  for (int i = 0; i < 64; ++i) {
    const double c = (i + 0.5) / 64;
    sum += (fresnel_conductor(float(c), float(n), float(k)) - (r + (1 - r) * std::pow(1 - c, 5))) * 2 * c / 64;
  }
  return sum;
}

}  // namespace

// The edge tint whose exact conductor reflects as much light in total as Schlick's
// F = r + (1 − r)(1 − cos θ)⁵, by bisection.
const std::array<float, 101>& schlick_matched_edge_tints() {
  static const std::array<float, 101> table = [] {
    std::array<float, 101> t{};
    for (int i = 0; i <= 100; ++i) {
      const double ri = std::min(i / 100.0, 0.999);
      double lo = 0, hi = 1;
      for (int it = 0; it < 30; ++it) {
        const double mid = (lo + hi) / 2;
        (albedo_difference(ri, mid) > 0 ? hi : lo) = mid;
      }
      t[i] = float((lo + hi) / 2);
    }
    return t;
  }();
  return table;
}

}  // namespace prism
