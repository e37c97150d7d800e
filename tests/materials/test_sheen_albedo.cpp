// SheenAlbedo: the sheen's albedo read along μ from its curve for one α (SheenAlbedo::Curve, what
// LayeredBsdf scales the layers beneath the sheen by) against the scaled Charlie lobe's directional
// albedo found here by quadrature, between the table's nodes.

#include <catch2/catch.hpp>
#include <cmath>

#include "materials/sheen_albedo.h"
#include "materials/sheen_bsdf.h"

using namespace prism;

namespace {

// E(μ) = ∫ f μ_i dω_i of the white lobe scaled as SheenBsdf scales it, by the midpoint rule in
// x = √μ_i (dμ_i = 2x dx: dense at grazing) and φ ∈ [0, 2π).
double albedo_by_quadrature(float alpha, float mu) {
  const CharlieSheen sheen(alpha);
  const Vec3f wo(std::sqrt(1 - mu * mu), 0, mu);
  constexpr int kX = 256, kPhi = 256;
  double sum = 0;
  for (int i = 0; i < kX; ++i) {
    const float x = (i + 0.5f) / kX, mu_i = x * x, sin_i = std::sqrt(1 - mu_i * mu_i);
    for (int j = 0; j < kPhi; ++j) {
      const float phi = 2 * kPi * (j + 0.5f) / kPhi;
      const Vec3f wi(sin_i * std::cos(phi), sin_i * std::sin(phi), mu_i);
      sum += sheen.value(wo, wi) * mu_i * 2 * x;
    }
  }
  return SheenAlbedo::scale(alpha) * sum * 2 * kPi / (kX * kPhi);
}

}  // namespace

TEST_CASE("the sheen's albedo curve gives the scaled Charlie lobe's directional albedo between the table's nodes") {
  for (const float alpha : {0.07f, 0.3f, 0.62f})
    for (const float mu : {0.13f, 0.42f, 0.77f, 0.97f}) {
      INFO("α " << alpha << ", μ " << mu);
      const double e = albedo_by_quadrature(alpha, mu);
      CHECK(SheenAlbedo::E(SheenAlbedo::curve(alpha), mu) == Approx(e).margin(1e-3));
    }
}
