#include "materials/sheen_albedo.h"

#include <algorithm>
#include <cmath>

#include "materials/sheen_bsdf.h"

namespace prism {

namespace {

// ∫ D G / (4 μ_o μ_i) μ_i dω_i by the midpoint rule in (μ_i, φ), φ over [0, π] by symmetry.
float directional_albedo(float mu, float alpha) {
  const CharlieSheen sheen(alpha);
  const Vec3f wo(std::sqrt(std::max(0.f, 1 - mu * mu)), 0, mu);
  constexpr int kTheta = 96, kPhi = 96;
  double sum = 0;
  for (int i = 0; i < kTheta; ++i) {
    const float mu_i = (i + 0.5f) / kTheta, sin_i = std::sqrt(1 - mu_i * mu_i);
    for (int j = 0; j < kPhi; ++j) {
      const float phi = kPi * (j + 0.5f) / kPhi;
      const Vec3f wi(sin_i * std::cos(phi), sin_i * std::sin(phi), mu_i);
      sum += sheen.value(wo, wi) * mu_i;
    }
  }
  return float(sum * 2 * kPi / (kTheta * kPhi));  // dω = dμ dφ; two halves of φ
}

}  // namespace

SheenAlbedo::SheenAlbedo() {
  for (int a = 0; a < kAlpha; ++a)
    for (int m = 0; m < kMu; ++m)
      e_[a * kMu + m] = directional_albedo(std::max(sqr(float(m) / (kMu - 1)), 1e-4f), float(a) / (kAlpha - 1));
}

const SheenAlbedo& SheenAlbedo::table() {
  static const SheenAlbedo t;
  return t;
}

float SheenAlbedo::E(float mu, float alpha) const {
  const float x = std::sqrt(std::clamp(mu, 0.f, 1.f)) * (kMu - 1), y = std::clamp(alpha, 0.f, 1.f) * (kAlpha - 1);
  const int i = std::min(int(x), kMu - 2), j = std::min(int(y), kAlpha - 2);
  const float tx = x - float(i), ty = y - float(j);
  const float* e = &e_[j * kMu + i];
  return (1 - ty) * ((1 - tx) * e[0] + tx * e[1]) + ty * ((1 - tx) * e[kMu] + tx * e[kMu + 1]);
}

}  // namespace prism
