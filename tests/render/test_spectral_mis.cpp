// Hero-wavelength spectral MIS at rough dispersive interfaces (materials/dispersive_bsdf.h): the
// same expectation as following the hero wavelength alone, with less colour noise, in a direct
// estimate at one interface and in whole renders (a white furnace, coloured lights seen through
// rough dispersive glass).

#include <catch2/catch.hpp>
#include <cmath>

#include "core/base/rng.h"
#include "materials/dispersive_bsdf.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Material rough_glass(IorModel ior, float roughness) {
  return Material{.name = "rough glass", .kind = PbrMaterial::glass(Dielectric(std::move(ior)), roughness)};
}

// Running mean and variance of a vector of three estimates.
struct Moments {
  std::array<double, 3> sum{}, sum2{};
  long n = 0;
  void add(const std::array<double, 3>& x) {
    for (int c = 0; c < 3; ++c) sum[c] += x[c], sum2[c] += x[c] * x[c];
    ++n;
  }
  double mean(int c) const { return sum[c] / n; }
  double variance(int c) const { return (sum2[c] - sum[c] * sum[c] / n) / (n - 1); }
  double standard_error(int c) const { return std::sqrt(variance(c) / n); }
};

// A coloured sky that varies with direction and wavelength, in [0.1, 1.9].
float sky(const Vec3f& w, float lambda) { return 1.f + 0.9f * w.x * std::sin(lambda / 30.f); }
// The colour band of a wavelength: blue, green, red.
int band(float lambda) { return lambda < 490.f ? 0 : lambda < 580.f ? 1 : 2; }

}  // namespace

TEST_CASE("spectral MIS at a rough dispersive interface: the hero's mean, less colour variance") {
  // The light one rough, strongly dispersive interface sends towards wo from the sky, in three
  // bands of wavelength: (1/N) Σ_k f_k |cos| L_k / (p̄ p(λ_k)) with every lane (spectral MIS),
  // against f_0 |cos| L_0 / (p_0 p(λ_0)) with the hero alone (the terminated secondaries), from
  // the same random numbers. Both are unbiased; they must agree within their standard errors.
  constexpr int N = 4;
  const Material glass = rough_glass(AbbeIor{1.7f, 20.f}, 0.3f);
  for (const Vec3f wo : {normalize(Vec3f(0.5f, 0.f, 0.866f)), normalize(Vec3f(0.3f, 0.1f, -0.95f))}) {
    INFO("wo " << wo.x << " " << wo.y << " " << wo.z);
    Moments mis, hero;
    Rng rng(7, 0);
    for (int i = 0; i < 100000; ++i) {
      const auto lambda = SampledWavelengths<N>::sample({rng.uniform(), rng.uniform()});
      const float uc = rng.uniform();
      const Vec2f u(rng.uniform(), rng.uniform());
      std::array<double, 3> a{}, h{};
      SampledSpectrum<N> path_pdfs(1.f);
      const DispersiveBsdf<N> bsdf(glass, {}, lambda, nullptr, path_pdfs);
      if (const auto s = bsdf.sample_f(wo, uc, u)) {
        REQUIRE(s->pdf > 0);
        for (int k = 0; k < N; ++k)
          a[band(lambda[k])] += s->f[k] * abs_cos_theta(s->wi) * sky(s->wi, lambda[k]) / (s->pdf * lambda.pdf()[k]) / N;
      }
      if (const auto s = bsdf_sample_f(make_bsdf(glass, {}, lambda.lane(0), nullptr), wo, uc, u))
        h[band(lambda[0])] += s->f[0] * abs_cos_theta(s->wi) * sky(s->wi, lambda[0]) / (s->pdf * lambda.pdf()[0]);
      mis.add(a), hero.add(h);
    }
    for (int c = 0; c < 3; ++c) {
      const double se = std::hypot(mis.standard_error(c), hero.standard_error(c));
      INFO("band " << c << ": spectral MIS " << mis.mean(c) << " ± " << mis.standard_error(c) << ", hero alone "
                   << hero.mean(c) << " ± " << hero.standard_error(c) << "; variance ratio "
                   << hero.variance(c) / mis.variance(c));
      CHECK(se < 0.01 * hero.mean(c));
      CHECK(std::abs(mis.mean(c) - hero.mean(c)) < 4.5 * se);
      CHECK(hero.variance(c) > 3 * mis.variance(c));
    }
  }
}

TEST_CASE(
    "spectral MIS through two rough dispersive interfaces in a row: the path's pdfs, not each vertex's, weigh the "
    "lanes") {
  // Light from the sky through two rough interfaces (the second sees the first's sample from the
  // other side, as the far face of a slab would): every lane divided by the product of the p̄,
  // which must be the lanes' path pdfs averaged, (1/N) Σ_j p_j(ω1) p_j(ω2), against the hero
  // alone. Averaging each vertex's pdfs on their own instead, Π_v (1/N) Σ_j p_j(ω_v), is biased.
  constexpr int N = 4;
  const Material glass = rough_glass(AbbeIor{1.7f, 20.f}, 0.1f);
  const Vec3f wo = normalize(Vec3f(0.5f, 0.f, 0.866f));
  Moments mis, hero;
  Rng rng(11, 0);
  for (int i = 0; i < 800000; ++i) {
    const auto lambda = SampledWavelengths<N>::sample({rng.uniform(), rng.uniform()});
    const float uc1 = rng.uniform(), uc2 = rng.uniform();
    const Vec2f u1(rng.uniform(), rng.uniform()), u2(rng.uniform(), rng.uniform());
    std::array<double, 3> a{}, h{};
    SampledSpectrum<N> path_pdfs(1.f);
    const DispersiveBsdf<N> first(glass, {}, lambda, nullptr, path_pdfs);
    if (const auto s1 = first.sample_f(wo, uc1, u1)) {
      const DispersiveBsdf<N> second(glass, {}, lambda, nullptr, path_pdfs);
      if (const auto s2 = second.sample_f(-s1->wi, uc2, u2))
        for (int k = 0; k < N; ++k)
          a[band(lambda[k])] += s1->f[k] * abs_cos_theta(s1->wi) * s2->f[k] * abs_cos_theta(s2->wi) *
                                sky(s2->wi, lambda[k]) / (s1->pdf * s2->pdf * lambda.pdf()[k]) / N;
    }
    const Bsdf<1> alone = make_bsdf(glass, {}, lambda.lane(0), nullptr);
    if (const auto s1 = bsdf_sample_f(alone, wo, uc1, u1))
      if (const auto s2 = bsdf_sample_f(alone, -s1->wi, uc2, u2))
        h[band(lambda[0])] += s1->f[0] * abs_cos_theta(s1->wi) * s2->f[0] * abs_cos_theta(s2->wi) *
                              sky(s2->wi, lambda[0]) / (s1->pdf * s2->pdf * lambda.pdf()[0]);
    mis.add(a), hero.add(h);
  }
  for (int c = 0; c < 3; ++c) {
    const double se = std::hypot(mis.standard_error(c), hero.standard_error(c));
    INFO("band " << c << ": spectral MIS " << mis.mean(c) << " ± " << mis.standard_error(c) << ", hero alone "
                 << hero.mean(c) << " ± " << hero.standard_error(c));
    CHECK(se < 0.01 * hero.mean(c));
    CHECK(std::abs(mis.mean(c) - hero.mean(c)) < 4.5 * se);
  }
}

TEST_CASE("furnace: a rough dispersive glass sphere under a uniform environment renders 1") {
  // Every lane keeps its own estimate through the rough interfaces; with the white sky every
  // direction brings 1, so each lane must stay 1 whatever its index (energy compensation makes the
  // rough interface lossless). Constant-index glass is the control.
  for (const IorModel& ior : {IorModel(ConstantIor{1.7f}), IorModel(AbbeIor{1.7f, 20.f})}) {
    Scene scene;
    scene.materials.push_back(rough_glass(ior, 0.5f));
    test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const auto img = test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 12, 12, 512, 64);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 12, 12, 1.0, 0.01);
  }
}

TEST_CASE("rough dispersive glass before coloured lights: 4 wavelengths by spectral MIS have the mean of 1") {
  // A rough flint sphere in front of a red and a blue panel, lit by them (light sampling at the
  // glass's vertices, MIS against its BSDF samples) and by a dim sky. Paths of one wavelength are
  // the plain estimator (each follows its own index); 4 wavelengths per path, weighed over the
  // lanes as heroes, must give the same image within noise, identically at any thread count.
  Scene scene;
  scene.materials.push_back(rough_glass(AbbeIor{1.7f, 20.f}, 0.3f));
  Material red = test::diffuse(Rgb{0, 0, 0}, "red"), blue = test::diffuse(Rgb{0, 0, 0}, "blue");
  red.emission = RgbIlluminantSpectrum(Rgb{3, 0.3f, 0.1f});
  blue.emission = RgbIlluminantSpectrum(Rgb{0.1f, 0.5f, 3});
  scene.materials.push_back(red), scene.materials.push_back(blue);
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  test::add_mesh(scene, test::make_quad({-2, -2, -2}, {2, 0, 0}, {0, 4, 0}, 1));
  test::add_mesh(scene, test::make_quad({0, -2, -2}, {2, 0, 0}, {0, 4, 0}, 2));
  scene.environment = RgbIlluminantSpectrum(Rgb{0.2f, 0.2f, 0.2f});
  const CameraDesc camera = test::look_at({0, 0, 5.f}, {0, 0, 0}, 20.f);
  RenderOptions options;
  options.spp = 1024;
  options.path.max_depth = 16;
  options.progress = false;
  options.seed = 3;
  options.wavelengths = 4;
  const auto mis = test::render_rgb(scene, camera, 12, 12, options);
  options.wavelengths = 1;
  options.seed = 4;
  const auto single = test::render_rgb(scene, camera, 12, 12, options);
  CHECK(mis.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    const auto d = test::mean_difference(mis, single, c);
    INFO("channel " << c << ": mean " << mis.mean(c) << ", difference " << d.difference << " ± " << d.standard_error);
    CHECK(d.standard_error < 0.01 * mis.mean(c));
    CHECK(std::abs(d.difference) < 4.5 * d.standard_error);
  }
  options.wavelengths = 4;
  options.seed = 3;
  options.threads = 1;
  CHECK(test::render_rgb(scene, camera, 12, 12, options).rgb == mis.rgb);
}
