#include "materials/sheen_albedo.h"

#include <algorithm>
#include <cmath>

#include "materials/sheen_bsdf.h"

namespace prism {

namespace {

float alpha_of(int node) { return sqr(float(node) / 31); }  // nodes uniform in √α

// ∫ D G / (4 μ_o μ_i) μ_i dω_i by the midpoint rule in (x, φ), μ_i = x² (dense at grazing,
// where the lobe of low roughness lies), φ over [0, π] by symmetry.
float directional_albedo(const CharlieSheen& sheen, float mu) {
  const Vec3f wo(std::sqrt(std::max(0.f, 1 - mu * mu)), 0, mu);
  constexpr int kX = 192, kPhi = 96;
  double sum = 0;
  for (int i = 0; i < kX; ++i) {
    const float x = (i + 0.5f) / kX, mu_i = x * x, sin_i = std::sqrt(1 - mu_i * mu_i);
    for (int j = 0; j < kPhi; ++j) {
      const float phi = kPi * (j + 0.5f) / kPhi;
      const Vec3f wi(sin_i * std::cos(phi), sin_i * std::sin(phi), mu_i);
      sum += sheen.value(wo, wi) * mu_i * 2 * x;  // dμ = 2x dx
    }
  }
  return float(sum * 2 * kPi / (kX * kPhi));  // dω = dμ dφ; two halves of φ
}

}  // namespace

const float* SheenAlbedo::row(int a) const {
  std::call_once(ready_[a], [this, a] {
    const CharlieSheen sheen(alpha_of(a));
    float peak = 1;
    for (int m = 0; m < kMu; ++m) {
      e_[a * kMu + m] = directional_albedo(sheen, std::max(sqr(float(m) / (kMu - 1)), 1e-4f));
      peak = std::max(peak, e_[a * kMu + m]);
    }
    for (int m = 0; m < kMu; ++m) e_[a * kMu + m] /= peak;
    scale_[a] = 1 / peak;
  });
  return &e_[a * kMu];
}

const SheenAlbedo& SheenAlbedo::table() {
  static const SheenAlbedo t;
  return t;
}

float SheenAlbedo::scale(float alpha) const {
  const float y = std::sqrt(std::clamp(alpha, 0.f, 1.f)) * (kAlpha - 1);
  const int j = std::min(int(y), kAlpha - 2);
  row(j), row(j + 1);
  return lerp(y - float(j), scale_[j], scale_[j + 1]);
}

float SheenAlbedo::E(float mu, float alpha) const {
  const float x = std::sqrt(std::clamp(mu, 0.f, 1.f)) * (kMu - 1);
  const float y = std::sqrt(std::clamp(alpha, 0.f, 1.f)) * (kAlpha - 1);
  const int i = std::min(int(x), kMu - 2), j = std::min(int(y), kAlpha - 2);
  const float tx = x - float(i), ty = y - float(j);
  row(j + 1);
  const float* e = row(j) + i;
  return (1 - ty) * ((1 - tx) * e[0] + tx * e[1]) + ty * ((1 - tx) * e[kMu] + tx * e[kMu + 1]);
}

}  // namespace prism
