// Thin-film interference (materials/thin_film.h) against an independent reference: the 2×2
// characteristic-matrix (transfer-matrix) method of Born & Wolf §1.6.2, in double, which never
// forms Airy's geometric series.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <complex>
#include <utility>

#include "materials/catalogue.h"
#include "materials/fresnel.h"
#include "materials/thin_film.h"

using namespace prism;

namespace {

using C = std::complex<double>;

// Reflectance of ambient | film | base for one polarisation by the characteristic matrix
//   M = [[cos β, −i sin β / Y_f], [−i Y_f sin β, cos β]],  β = 2π d q_f / λ,
//   r = (Y_a m11 + Y_a Y_b m12 − m21 − Y_b m22) / (Y_a m11 + Y_a Y_b m12 + m21 + Y_b m22),
// with the optical admittances Y = q (s) or n²/q (p), q = √(n² − n_a² sin²θ_a).
double tmm_reflectance(bool p, double cos_a, double lambda, double d, double na, double nf, C nb) {
  const double s2 = na * na * (1 - cos_a * cos_a);
  const C qa(na * cos_a), qf = std::sqrt(C(nf * nf) - s2), qb = std::sqrt(nb * nb - s2);
  const auto Y = [p](C n, C q) { return p ? n * n / q : q; };
  const C ya = Y(na, qa), yf = Y(nf, qf), yb = Y(nb, qb);
  const C beta = 2 * 3.14159265358979323846 * d * qf / lambda;
  const C i(0, 1);
  const C m11 = std::cos(beta), m12 = -i * std::sin(beta) / yf, m21 = -i * yf * std::sin(beta), m22 = std::cos(beta);
  const C num = ya * m11 + ya * yb * m12 - m21 - yb * m22, den = ya * m11 + ya * yb * m12 + m21 + yb * m22;
  return std::norm(num / den);
}

double tmm(double cos_a, double lambda, double d, double na, double nf, C nb) {
  return (tmm_reflectance(false, cos_a, lambda, d, na, nf, nb) + tmm_reflectance(true, cos_a, lambda, d, na, nf, nb)) /
         2;
}

}  // namespace

TEST_CASE("thin film: Airy's sum equals the transfer-matrix reference over dielectric and metal bases") {
  const MeasuredMetal au = MaterialCatalogue::standard().metal("Au");
  for (double lambda : {380.0, 450.0, 550.0, 640.0, 720.0})
    for (double d : {0.0, 1.0, 50.0, 137.0, 300.0, 611.0, 900.0, 1200.0})
      for (double cos_a : {1.0, 0.8, 0.5, 0.2, 0.02})
        for (double nf : {1.0, 1.3, 1.8, 2.4}) {
          const C bases[] = {C(1.5), C(1.0), C(1.33), C(evaluate(au.n, float(lambda)), evaluate(au.k, float(lambda)))};
          for (const C nb : bases) {
            INFO("λ " << lambda << " d " << d << " cos " << cos_a << " n_film " << nf << " base " << nb);
            CHECK(thin_film_reflectance(cos_a, lambda, d, 1.0, nf, std::complex<float>(nb)) ==
                  Approx(tmm(cos_a, lambda, d, 1.0, nf, nb)).margin(1e-4));
          }
          // Seen from inside glass (n 1.5) through the film into air: total internal reflection
          // past the critical angle, evanescent in the film.
          INFO("from glass: λ " << lambda << " d " << d << " cos " << cos_a << " n_film " << nf);
          CHECK(thin_film_reflectance(cos_a, lambda, d, 1.5, nf, 1.f) ==
                Approx(tmm(cos_a, lambda, d, 1.5, nf, C(1.0))).margin(1e-4));
        }
}

TEST_CASE("thin film: no thickness, or the ambient's index, leaves the bare base's Fresnel reflectance") {
  const MeasuredMetal cu = MaterialCatalogue::standard().metal("Cu");
  for (float lambda : {400.f, 550.f, 700.f})
    for (float cos_a : {1.f, 0.6f, 0.1f}) {
      const float n = evaluate(cu.n, lambda), k = evaluate(cu.k, lambda);
      CHECK(thin_film_reflectance(cos_a, lambda, 0, 1, 1.6, {n, k}) ==
            Approx(fresnel_conductor(cos_a, n, k)).margin(1e-6));
      CHECK(thin_film_reflectance(cos_a, lambda, 0, 1, 1.6, 1.5f) ==
            Approx(fresnel_dielectric(cos_a, 1.5f)).margin(1e-6));
      for (double d : {100.0, 750.0}) {
        CHECK(thin_film_reflectance(cos_a, lambda, d, 1, 1, {n, k}) ==
              Approx(fresnel_conductor(cos_a, n, k)).margin(1e-6));
        CHECK(thin_film_reflectance(cos_a, lambda, d, 1, 1, 1.5f) ==
              Approx(fresnel_dielectric(cos_a, 1.5f)).margin(1e-6));
      }
    }
}

TEST_CASE("thin film: a quarter-wave film of index √n on glass is an anti-reflection coating") {
  const double n = 1.5, nf = std::sqrt(n), lambda = 550, d = lambda / (4 * nf);
  CHECK(thin_film_reflectance(1, lambda, d, 1, nf, float(n)) == Approx(0).margin(1e-6));
  // Half-wave: absent at its design wavelength.
  CHECK(thin_film_reflectance(1, lambda, 2 * d, 1, nf, float(n)) == Approx(0.04).margin(1e-6));
}

TEST_CASE(
    "thin film: the build-time excess table holds the largest of each cell's corners, and bounds the film over its "
    "coupling") {
  using namespace albedo_tables;
  // Each cell holds the largest of the direct computation at its four corners.
  for (const auto& [a, b] : {std::pair{0, 0}, {10, 10}, {16, 10}, {33, 7}, {39, 39}, {5, 38}}) {
    float corners = 0;
    for (const auto& [da, db] : {std::pair{0, 0}, {0, 1}, {1, 0}, {1, 1}})
      corners = std::max(corners, film_reflectance_excess_exact(film_index_of(a + da), film_index_of(b + db)));
    CHECK(film_excess[a * kFilmSteps + b] == Approx(corners).margin(1e-6));
  }
  // Between the nodes, the lookup (a cell's largest corner) still bounds what the film reflects
  // above F(θ, η_c), at any thickness and angle (checked against the double-precision reference).
  for (const auto& [nf, eta] : {std::pair{1.83, 1.47}, {1.31, 1.52}, {2.37, 1.12}}) {
    const double eta_c = film_coupling_index(float(nf), float(eta));
    const double x = film_reflectance_excess(float(nf), float(eta));
    double worst = -1;
    for (int j = 0; j <= 90; ++j)
      for (double d = 0; d <= 1200; d += 10) {
        const double c = std::cos(j * 3.14159265358979323846 / 180);
        worst = std::max(worst, tmm(c, 550, d, 1, nf, eta) - fresnel_dielectric(float(c), float(eta_c)));
      }
    CHECK(worst <= x + 1e-4);
  }
  // The lanes' lookup is the one-lane lookup on each lane, with all lanes in the table or some outside it.
  SampledSpectrum<8> nf, eta;
  for (int i = 0; i < 8; ++i) nf[i] = 1.2f + 0.17f * float(i), eta[i] = 2.9f - 0.23f * float(i);
  for (int outside : {0, 1}) {
    if (outside) eta[5] = 3.4f;
    const SampledSpectrum<8> x = film_reflectance_excess(nf, eta);
    for (int i = 0; i < 8; ++i) CHECK(x[i] == film_reflectance_excess(nf[i], eta[i]));
  }
}

TEST_CASE("thin film: each lane of a path equals the transfer-matrix reference, over a dielectric and a metal") {
  // The lanes' own base indices (a specular colour's), from outside (the real-arithmetic sum) and
  // from inside the dielectric (the complex one), and a metal's n + ik, blended by the weight.
  const auto lambda = SampledWavelengths<8>::sample({0.37f, 0.2f});
  const MeasuredMetal au = MaterialCatalogue::standard().metal("Au");
  for (float d : {0.f, 137.f, 250.f, 1200.f})
    for (float nf : {1.3f, 1.6f, 2.4f})
      for (float weight : {1.f, 0.5f}) {
        const FilmLanes<8> film(ThinFilm{weight, d, nf}, lambda, SampledSpectrum<8>(1.f));
        const auto eta = [](int i) { return 1.2f + 0.1f * i; };
        const auto metal = [&](int i) {
          return std::complex<float>(evaluate(au.n, lambda[i]), evaluate(au.k, lambda[i]));
        };
        for (float cos_a : {1.f, 0.7f, 0.3f, 0.05f}) {
          const SampledSpectrum<8> outside = film.reflectance(cos_a, eta), inside = film.reflectance(-cos_a, eta),
                                   on_metal = film.reflectance(cos_a, metal);
          for (int i = 0; i < 8; ++i) {
            INFO("λ " << lambda[i] << " d " << d << " n_film " << nf << " weight " << weight << " cos " << cos_a);
            const auto blend = [&](double filmed, double bare) { return bare + weight * (filmed - bare); };
            CHECK(outside[i] ==
                  Approx(blend(tmm(cos_a, lambda[i], d, 1, nf, eta(i)), tmm(cos_a, lambda[i], 0, 1, nf, eta(i))))
                      .margin(1e-4));
            CHECK(inside[i] ==
                  Approx(blend(tmm(cos_a, lambda[i], d, eta(i), nf, 1), tmm(cos_a, lambda[i], 0, eta(i), nf, 1)))
                      .margin(1e-4));
            CHECK(on_metal[i] ==
                  Approx(blend(tmm(cos_a, lambda[i], d, 1, nf, metal(i)), tmm(cos_a, lambda[i], 0, 1, nf, metal(i))))
                      .margin(1e-4));
          }
        }
      }
}
