// Furnace tests: scenes whose exact answer is known. A convex Lambertian object under a uniform
// environment of radiance 1 reflects its albedo (every point sees only the environment); inside
// a closed sphere of albedo ρ that emits Le, every point sees Le / (1 − ρ).

#include <catch2/catch.hpp>
#include <cmath>

#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// Renders a Lambertian sphere of the given albedo under a uniform environment of radiance 1.
// (Many samples: the blue channel, built mostly from z̄ near 450 nm where the visible pdf is low,
// is the noisiest, and the checks require its standard error to be ≤ 0.0025.)
test::TestRender render_env_furnace(float albedo, int spp) {
  Scene scene;
  scene.materials.push_back(test::diffuse({albedo, albedo, albedo}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  return test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 30.f), 32, 32, spp);
}

}  // namespace

TEST_CASE("furnace: albedo-1 sphere under a uniform environment of radiance 1 renders 1") {
  const auto img = render_env_furnace(1.f, 1024);
  CHECK(img.stats.invalid_samples == 0);
  test::check_mean(img, 0, 0, 32, 32, 1.0, 0.01);
  // The centre of the image is all sphere: the object itself, not just the background, is right.
  test::check_mean(img, 10, 10, 22, 22, 1.0, 0.01);
}

TEST_CASE("furnace: albedo-0.5 sphere under a uniform environment renders 0.5") {
  const auto img = render_env_furnace(0.5f, 1024);
  test::check_mean(img, 10, 10, 22, 22, 0.5, 0.01);
  test::check_mean(img, 0, 0, 32, 3, 1.0, 0.01);  // top rows: sky
}

TEST_CASE("furnace: inside a closed emitting sphere the radiance is Le / (1 - albedo)") {
  // Albedo 0.5, Le 0.5: L = 1 after infinitely many bounces (Russian roulette keeps it unbiased).
  const Scene scene = test::emitting_sphere_scene();
  const auto img = test::render_rgb(scene, test::look_at({0, 0, 0.3f}, {0, 0, -1}, 60.f), 32, 32, 128, 1000);
  CHECK(img.stats.invalid_samples == 0);
  test::check_mean(img, 0, 0, 32, 32, 1.0, 0.01);
}

TEST_CASE("Russian roulette never cuts short a ray that leaves for the sky") {
  // A periscope of two grey mirrors under a uniform sky: every camera ray reflects off both and
  // leaves upwards. Roulette is decided where a path meets its third surface, so these paths,
  // whose throughput after two bounces (F² ≈ 0.25) would end one in two of them, all reach the sky:
  // the image equals the one rendered without roulette, sample for sample.
  Scene scene;
  Material mirror{.name = "mirror", .kind = PbrMaterial::metal_of(Rgb{0.5f, 0.5f, 0.5f}, 0)};
  scene.materials.push_back(std::move(mirror));
  test::add_mesh(scene,
                 test::make_quad({-0.5f, -1, 0.5f}, {1, 0, -1}, {0, 2, 0}, 0));  // faces (1, 0, 1): sends -z to +x
  test::add_mesh(scene,
                 test::make_quad({2.5f, -1, -0.5f}, {1, 0, 1}, {0, 2, 0}, 0));  // faces (-1, 0, 1): sends +x to +z
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  RenderOptions o;
  o.spp = 4;
  o.progress = false;
  const auto camera = test::look_at({0, 0, 2}, {0, 0, 0}, 8.f);
  const auto with = test::render_rgb(scene, camera, 8, 8, o);
  o.path.russian_roulette = false;
  const auto without = test::render_rgb(scene, camera, 8, 8, o);
  CHECK(with.stats.invalid_samples == 0);
  for (size_t i = 0; i < with.rgb.size(); ++i) {
    INFO("value " << i);
    REQUIRE(without.rgb[i] > 0.1f);
    CHECK(with.rgb[i] == without.rgb[i]);
  }
}

TEST_CASE("images are identical whatever the thread count") {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.7f, 0.4f, 0.2f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 2, 0));
  scene.point_lights.push_back({"lamp", {2, 2, 2}, RgbIlluminantSpectrum(Rgb{10, 10, 10})});
  scene.environment = RgbIlluminantSpectrum(Rgb{0.2f, 0.3f, 0.5f});
  const auto camera = test::look_at({0, 0, 4}, {0, 0, 0}, 40.f);
  const auto one = test::render_rgb(scene, camera, 40, 30, 4, 16, 7, 1);
  const auto two = test::render_rgb(scene, camera, 40, 30, 4, 16, 7, 2);
  CHECK(one.rgb == two.rgb);
  const auto other_seed = test::render_rgb(scene, camera, 40, 30, 4, 16, 8, 2);
  CHECK(one.rgb != other_seed.rgb);
}

TEST_CASE("furnace: unbiased with the Sobol sampler and with BSDF sampling only") {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.5f, 0.5f, 0.5f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  for (const bool sobol : {true, false}) {
    RenderOptions options;
    options.spp = 1024;
    options.sampler = sobol ? SamplerKind::sobol : SamplerKind::independent;
    options.path.next_event = !sobol;  // Sobol with NEE+MIS; independent with BSDF sampling only
    const auto img = test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 16, 16, options);
    INFO((sobol ? "sobol" : "BSDF sampling only"));
    test::check_mean(img, 0, 0, 16, 16, 0.5, 0.01);
  }
}

TEST_CASE("furnace: the default Sobol sampler converges at least as fast as independent samples") {
  // A sphere of albedo 0.5 filling the image under a uniform environment of radiance 1: every
  // pixel's exact value is 0.5, so the image's MSE is the estimator's. Reported per doubling of
  // the spp (0.5 is the Monte Carlo rate; stratification does better).
  Scene scene;
  scene.materials.push_back(test::diffuse({0.5f, 0.5f, 0.5f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  const auto mse = [&](SamplerKind kind, int spp) {
    RenderOptions options;
    options.spp = spp;
    options.sampler = kind;
    const auto img = test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 16, 16, options);
    double se = 0;
    for (float v : img.rgb) se += sqr(double(v) - 0.5);
    return se / double(img.rgb.size());
  };
  double first[2] = {}, last[2] = {};
  for (const int spp : {4, 16, 64}) {
    const double sobol = mse(SamplerKind::sobol, spp), independent = mse(SamplerKind::independent, spp);
    WARN(spp << " spp: MSE Sobol " << sobol << ", independent " << independent);
    CHECK(sobol <= independent);
    if (spp == 4) first[0] = sobol, first[1] = independent;
    last[0] = sobol, last[1] = independent;
  }
  const double sobol_rate = std::pow(last[0] / first[0], 1.0 / 4),
               independent_rate = std::pow(last[1] / first[1], 1.0 / 4);
  WARN("MSE per doubling of spp, 4 to 64: Sobol x" << sobol_rate << ", independent x" << independent_rate);
  CHECK(sobol_rate <= 0.55);
}

TEST_CASE("furnace: rough white metal spheres render 1 with multiple-scattering compensation") {
  // Lossless (white) metal at roughness 0.3, 0.6 and 1, side by side so that light also bounces
  // between them, under a uniform environment of radiance 1: everything reflects everything, so the
  // image is 1 everywhere. Single scattering loses up to ~60% per bounce at roughness 1 (the control).
  for (const bool compensated : {true, false}) {
    Scene scene;
    for (float roughness : {0.3f, 0.6f, 1.f}) {
      Material m{.name = "white metal", .kind = PbrMaterial::metal_of(Rgb{1, 1, 1}, roughness)};
      std::get<PbrMaterial>(m.kind).energy_compensation = compensated;
      scene.materials.push_back(m);
    }
    for (uint32_t i = 0; i < 3; ++i) test::add_mesh(scene, test::make_icosphere({float(i) - 1.f, 0, 0}, 0.55f, 3, i));
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const auto img = test::render_rgb(scene, test::look_at({0, 0, 6.f}, {0, 0, 0}, 12.f), 32, 16, 1024, 64);
    CHECK(img.stats.invalid_samples == 0);
    INFO((compensated ? "compensated" : "single scattering") << ": mean " << img.mean(0, 0, 4, 32, 12));
    if (compensated)
      test::check_mean(img, 0, 4, 32, 12, 1.0, 0.01);
    else
      CHECK(img.mean(1, 0, 4, 32, 12) < 0.9);
  }
}
