#include "materials/material.h"

#include <array>

#include "materials/fresnel.h"

namespace prism {

namespace {

// Gulbrandsen 2014 ("Artist Friendly Metallic Fresnel", JCGT 3(4)): the n, k whose normal
// reflectance is r, with edge tint g ∈ [0, 1] blending n between (1 − r)/(1 + r) and
// (1 + √r)/(1 − √r).
std::array<double, 2> gulbrandsen_nk(double r, double g) {
  const double sr = std::sqrt(r);
  const double n = g * (1 - r) / (1 + r) + (1 - g) * (1 + sr) / (1 - sr);
  const double k2 = (r * (n + 1) * (n + 1) - (n - 1) * (n - 1)) / (1 - r);
  return {n, std::sqrt(std::max(k2, 0.0))};
}

// Directional albedo difference ∫ (F_exact − F_Schlick) 2cos θ dcos θ (64-point midpoint rule).
double albedo_difference(double r, double g) {
  const auto [n, k] = gulbrandsen_nk(r, g);
  double sum = 0;
  for (int i = 0; i < 64; ++i) {
    const double c = (i + 0.5) / 64;
    sum += (fresnel_conductor(float(c), float(n), float(k)) - (r + (1 - r) * std::pow(1 - c, 5))) * 2 * c / 64;
  }
  return sum;
}

// The edge tint at which the exact conductor reflects as much light in total as glTF's
// reference metal (Schlick's F = r + (1 − r)(1 − cos θ)⁵), by bisection, tabulated in r.
double schlick_matched_edge_tint(double r) {
  static const std::array<double, 101> table = [] {
    std::array<double, 101> t{};
    for (int i = 0; i <= 100; ++i) {
      const double ri = std::min(i / 100.0, 0.999);
      double lo = 0, hi = 1;
      for (int it = 0; it < 30; ++it) {
        const double mid = (lo + hi) / 2;
        (albedo_difference(ri, mid) > 0 ? hi : lo) = mid;
      }
      t[i] = (lo + hi) / 2;
    }
    return t;
  }();
  const double x = std::clamp(r, 0.0, 1.0) * 100;
  const int i = std::min(int(x), 99);
  return table[i] + (x - i) * (table[i + 1] - table[i]);
}

}  // namespace

ConductorMaterial conductor_from_reflectance(const Spectrum& reflectance) {
  std::vector<float> n, k;
  for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l) {
    const double r = std::clamp(double(evaluate(reflectance, float(l))), 0.0, 0.999);  // r < 1 keeps k finite
    const auto nk = gulbrandsen_nk(r, schlick_matched_edge_tint(r));
    n.push_back(float(nk[0]));
    k.push_back(float(nk[1]));
  }
  return {DenselySampledSpectrum(int(kLambdaMin), n), DenselySampledSpectrum(int(kLambdaMin), k), {}};
}

}  // namespace prism
