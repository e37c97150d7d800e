// SpecularAlbedo::curve, the E(μ) of one lobe's α and η interpolated along μ once, against the
// lanes' look-up (at_lanes, from the α's slice of the tables), and that against the white lobe's.

#include <array>
#include <catch2/catch.hpp>
#include <cmath>

#include "core/base/rng.h"
#include "materials/microfacet.h"
#include "materials/specular_albedo.h"

using namespace prism;

TEST_CASE(
    "a lobe's albedo curve gives the tables' E(μ) and E_avg at any α, η and μ, and the exact Fresnel when smooth") {
  const SpecularAlbedo& table = SpecularAlbedo::table();
  Rng rng(7, 0);
  for (const bool compensated : {false, true}) {
    for (int k = 0; k < 2000; ++k) {
      // α over the tables' range and below the smooth threshold; η across both sides' span.
      const float alpha = k % 10 == 0 ? 5e-4f : std::pow(rng.uniform(), 3.f);
      const float eta = 1.f / 3 + rng.uniform() * (3 - 1.f / 3);
      const float mu = k % 7 == 0 ? 0.f : rng.uniform();
      INFO("α " << alpha << ", η " << eta << ", μ " << mu << ", compensated " << compensated);
      const SpecularAlbedo::Roughness r = SpecularAlbedo::roughness(alpha);
      const SpecularAlbedo::Curve curve = table.curve(r, eta, compensated);
      const SpecularAlbedo::Lanes<1> lane(std::array<float, 1>{eta});
      const SpecularAlbedo::AtLanes<1> at = table.at_lanes(mu, r, lane, compensated);
      CHECK(SpecularAlbedo::E(curve, mu) == Approx(at.e[0]).margin(1e-6));
      CHECK(at.white == Approx(table.white(mu, r)).margin(1e-6));
      CHECK(curve.average == Approx(table.average(r, lane, compensated)[0]).margin(1e-6));
      if (TrowbridgeReitz::effectively_smooth(alpha))
        CHECK(SpecularAlbedo::E(curve, mu) == fresnel_dielectric(mu, eta));
    }
  }
}
