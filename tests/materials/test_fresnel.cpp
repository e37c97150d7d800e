// Fresnel equations and refraction against measured and analytic values, and their stability
// on extreme inputs.

#include <catch2/catch.hpp>

#include "core/base/rng.h"
#include "core/base/warp.h"
#include "materials/catalogue.h"
#include "materials/fresnel.h"

using namespace prism;

namespace {
float cos_deg(float degrees) { return std::cos(radians(degrees)); }

// The widespread approximation |r∥|², |r⊥|² in n, k and cos θ (e.g. pbrt-v3's FrConductor;
// Born & Wolf §14.2 with a² + b² written out): a cross-check of the exact complex formula only.
float conductor_approximation(float cos_i, float n, float k) {
  const double c2 = cos_i * cos_i, s2 = 1 - c2, n2 = n * n, k2 = k * k;
  const double t0 = n2 - k2 - s2, a2b2 = std::sqrt(t0 * t0 + 4 * n2 * k2), a = std::sqrt(0.5 * (a2b2 + t0));
  const double t1 = a2b2 + c2, t2 = 2 * cos_i * a;
  const double rs = (t1 - t2) / (t1 + t2);
  const double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
  const double rp = rs * (t3 - t4) / (t3 + t4);
  return float((rs + rp) / 2);
}
}  // namespace

TEST_CASE("copper (Johnson & Christy 1972) at 550 nm reflects as measured") {
  const MeasuredMetal cu = MaterialCatalogue::standard().metal("Cu");
  const float n = evaluate(cu.n, 550), k = evaluate(cu.k, 550);
  const float angles[] = {0, 45, 60, 80, 89};
  const float expected[] = {0.6235f, 0.6221f, 0.6254f, 0.7300f, 0.9606f};
  for (int i = 0; i < 5; ++i) {
    INFO("angle " << angles[i]);
    CHECK(fresnel_conductor(cos_deg(angles[i]), n, k) == Approx(expected[i]).margin(2e-3));
    CHECK(conductor_approximation(cos_deg(angles[i]), n, k) ==
          Approx(fresnel_conductor(cos_deg(angles[i]), n, k)).margin(1e-5));
  }
}

TEST_CASE("gold and silver normal-incidence reflectance at 450, 550, 650 nm") {
  const auto check = [](const char* key, std::array<float, 3> expected) {
    const MeasuredMetal m = MaterialCatalogue::standard().metal(key);
    const float lambdas[] = {450, 550, 650};
    for (int i = 0; i < 3; ++i) {
      INFO(key << " at " << lambdas[i] << " nm");
      CHECK(fresnel_conductor(1, evaluate(m.n, lambdas[i]), evaluate(m.k, lambdas[i])) ==
            Approx(expected[i]).margin(3e-3));
    }
  };
  check("Au", {0.408f, 0.792f, 0.957f});
  check("Ag", {0.980f, 0.983f, 0.990f});
}

TEST_CASE("every catalogue metal is a metal over the visible range") {
  for (const auto& e : MaterialCatalogue::standard().entries()) {
    if (!e.metal) continue;
    const MeasuredMetal m = MaterialCatalogue::standard().metal(e.key);
    for (float l = kLambdaMin; l <= kLambdaMax; l += 10) {
      INFO(e.key << " at " << l << " nm");
      const float n = evaluate(m.n, l), k = evaluate(m.k, l);
      REQUIRE(n > 0);
      REQUIRE(k > n * 0.5f);  // strongly absorbing: Re(ε) = n² − k² is negative or small
      const float R = fresnel_conductor(1, n, k);
      REQUIRE(R > 0.3f);
      REQUIRE(R < 1);
    }
  }
}

TEST_CASE("N-BK7 at 587.6 nm: index, reflectance, Brewster and critical angles") {
  const IorModel bk7 = MaterialCatalogue::standard().dielectric("N-BK7");
  const float n = ior(bk7, 587.56f);
  CHECK(n == Approx(1.51680).margin(1e-5));
  CHECK(abbe_number(bk7) == Approx(64.17).margin(0.05));
  CHECK(fresnel_dielectric(1, n) == Approx(0.04216).margin(2e-5));
  // Brewster: tan θ_B = n, where p-polarised light is not reflected.
  const float brewster = degrees(std::atan(n));
  CHECK(brewster == Approx(56.604).margin(1e-3));
  CHECK(fresnel_dielectric_polarized(std::cos(std::atan(n)), n).Rp == Approx(0).margin(1e-8));
  CHECK(fresnel_dielectric_polarized(std::cos(std::atan(n)), n).Rs > 0.1f);
  // Critical angle glass → air: sin θ_c = 1/n; from inside, cos θ_i < 0 flips η.
  const float critical = degrees(std::asin(1 / n));
  CHECK(critical == Approx(41.245).margin(1e-3));
  CHECK(fresnel_dielectric(-cos_deg(critical + 0.01f), n) == 1.f);
  CHECK(fresnel_dielectric(-cos_deg(critical - 0.01f), n) < 1.f);
  CHECK_FALSE(refract(Vec3f(std::sin(radians(critical + 0.01f)), 0, -cos_deg(critical + 0.01f)), {0, 0, 1}, n));
  CHECK(refract(Vec3f(std::sin(radians(critical - 0.01f)), 0, -cos_deg(critical - 0.01f)), {0, 0, 1}, n));
}

TEST_CASE("Snell's law: refracted directions obey n1 sin θ1 = n2 sin θ2 and invert") {
  Rng rng(5, 0);
  for (int i = 0; i < 1000; ++i) {
    const Vec3f w = sample_uniform_hemisphere({rng.uniform(), rng.uniform()});
    const float eta = 1.f + 2.f * rng.uniform();
    const auto t = refract(w, {0, 0, 1}, eta);
    REQUIRE(t);
    const float sin_i = std::sqrt(std::max(0.f, 1 - w.z * w.z)),
                sin_t = std::sqrt(std::max(0.f, 1 - t->wt.z * t->wt.z));
    CHECK(sin_i == Approx(eta * sin_t).margin(1e-5));
    CHECK(t->wt.z < 0);
    const auto back = refract(t->wt, {0, 0, 1}, eta);  // reversibility: from inside back out along w
    REQUIRE(back);
    CHECK(length(back->wt - w) == Approx(0).margin(1e-4));
  }
}

TEST_CASE("dielectric reflectance is reciprocal: the same from both sides of an interface (Stokes)") {
  for (float eta : {1.2f, 1.5f, 2.42f})
    for (float deg = 0; deg < 89.9f; deg += 5) {
      const Vec3f w(std::sin(radians(deg)), 0, cos_deg(deg));
      const auto t = refract(w, {0, 0, 1}, eta);
      REQUIRE(t);
      // R seen from outside at θ_i equals R seen from inside at θ_t.
      CHECK(fresnel_dielectric(w.z, eta) == Approx(fresnel_dielectric(t->wt.z, eta)).margin(1e-6));
    }
}

TEST_CASE("index-matched interface: no reflection, straight through") {
  for (float c : {1.f, 0.7f, 0.1f, -0.5f}) CHECK(fresnel_dielectric(c, 1.f) == 0.f);
  const Vec3f w = normalize(Vec3f(0.3f, -0.2f, 0.9f));
  const auto t = refract(w, {0, 0, 1}, 1.f);
  REQUIRE(t);
  CHECK(length(t->wt + w) == Approx(0).margin(1e-6));
}

TEST_CASE("Fresnel equations stay finite and between 0 and 1 on extreme inputs") {
  const float cosines[] = {-1, -0.5f, -1e-6f, -0.f, 0, 1e-7f, 1e-6f, 0.5f, 0.999999f, 1};
  const float etas[] = {1e-3f, 0.1f, 0.5f, 0.9999f, 1, 1.0001f, 1.5f, 4, 10, 1e3f};
  const float ks[] = {0, 1e-6f, 1e-3f, 1, 10, 100, 1e3f};
  for (float c : cosines)
    for (float eta : etas) {
      const auto d = fresnel_dielectric_polarized(c, eta);
      for (float r : {d.R, d.Rs, d.Rp}) {
        INFO("cos " << c << " eta " << eta);
        REQUIRE(std::isfinite(r));
        REQUIRE(r >= 0);
        REQUIRE(r <= 1);
      }
      for (float k : ks) {
        const auto m = fresnel_conductor_polarized(c, eta, k);
        for (float r : {m.R, m.Rs, m.Rp}) {
          INFO("cos " << c << " n " << eta << " k " << k);
          REQUIRE(std::isfinite(r));
          REQUIRE(r >= 0);
          REQUIRE(r <= 1);
        }
      }
      const Vec3f w(std::sqrt(std::max(0.f, 1 - c * c)), 0, c);
      if (const auto t = refract(w, {0, 0, 1}, eta)) REQUIRE(is_finite(t->wt));
    }
  // Grazing incidence reflects everything; a perfect conductor (k → ∞) too.
  CHECK(fresnel_dielectric(0, 1.5f) == Approx(1));
  CHECK(fresnel_conductor(0, 0.2f, 3.f) == Approx(1));
  CHECK(fresnel_conductor(1, 1.f, 1e3f) == Approx(1).margin(1e-5));
  // η = 0, the ideal-conductor limit: everything, both polarisations, at every angle.
  for (const float c : {0.f, 0.3f, 0.7071f, 1.f}) {
    const FresnelReflectance r = fresnel_conductor_polarized(c, 0, 0);
    CHECK(r.R == 1);
    CHECK(r.Rs == 1);
    CHECK(r.Rp == 1);
  }
  // Huge index ratios reflect almost everything at normal incidence: ((η−1)/(η+1))².
  CHECK(fresnel_dielectric(1, 1e3f) == Approx(sqr((1e3 - 1) / (1e3 + 1))).epsilon(1e-5));
  CHECK(fresnel_dielectric(1, 1e-3f) == Approx(sqr((1e-3 - 1) / (1e-3 + 1))).epsilon(1e-5));
}

TEST_CASE("dispersion models: KHR_materials_dispersion's Abbe form and Sellmeier glasses") {
  // Abbe form passes through n_d at 587.56 nm and reproduces V_d.
  const IorModel abbe = AbbeIor{1.5f, 40.f};
  CHECK(ior(abbe, 587.56f) == Approx(1.5).margin(1e-4));
  CHECK(abbe_number(abbe) == Approx(40).epsilon(5e-3));
  CHECK(is_dispersive(abbe));
  CHECK_FALSE(is_dispersive(ConstantIor{1.5f}));
  const IorModel sf11 = MaterialCatalogue::standard().dielectric("N-SF11");
  CHECK(ior(sf11, 587.56f) == Approx(1.78472).margin(1e-5));
  CHECK(abbe_number(sf11) == Approx(25.68).margin(0.05));
  CHECK(ior(sf11, 450) > ior(sf11, 650));  // normal dispersion: blue bends more
  CHECK(ior(CauchyIor{1.5f, 0.004f}, 500) == Approx(1.5 + 0.004 / 0.25));
  // Tabulated n(λ): linear between measured points, dispersive when they differ.
  const IorModel table = TabulatedIor{TabulatedSpectrum({400, 500, 700}, {1.343f, 1.337f, 1.331f})};
  CHECK(ior(table, 450) == Approx(1.340));
  CHECK(ior(table, 600) == Approx(1.334));
  CHECK(is_dispersive(table));
  CHECK_FALSE(is_dispersive(TabulatedIor{TabulatedSpectrum({400, 700}, {1.5f, 1.5f})}));
}

TEST_CASE("catalogue materials are finite at the ends of the wavelength range") {
  for (const auto& e : MaterialCatalogue::standard().entries())
    for (const float l : {kLambdaMin, kLambdaMax}) {
      INFO(e.key << " at " << l << " nm");
      if (e.metal) {
        const MeasuredMetal m = MaterialCatalogue::standard().metal(e.key);
        const float R = fresnel_conductor(0.3f, evaluate(m.n, l), evaluate(m.k, l));
        CHECK(R > 0);
        CHECK(R < 1);
      } else {
        const float n = ior(MaterialCatalogue::standard().dielectric(e.key), l);
        CHECK(n > 1);
        CHECK(n < 3);
      }
    }
}
