// Fresnel surfaces in whole renders: glass neither creates nor loses energy, Beer–Lambert
// absorption is exact, dispersion keeps the hero wavelength, and the Whitted and path
// integrators agree.

#include <catch2/catch.hpp>

#include "core/render/path_integrator.h"
#include "core/render/whitted_integrator.h"
#include "materials/catalogue.h"
#include "materials/make_bsdf.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Material glass(IorModel ior, std::optional<Spectrum> absorption = {}) {
  return Material{.name = "glass",
                  .kind = PbrMaterial::glass(Dielectric(std::move(ior), Medium{.sigma_a = std::move(absorption)}))};
}

// A closed glass icosphere under a uniform environment of radiance 1, filling the image.
test::TestRender render_glass_furnace(IorModel ior, int spp) {
  Scene scene;
  scene.materials.push_back(glass(std::move(ior)));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  return test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 16, 16, spp, 1000);
}

}  // namespace

TEST_CASE("furnace: a clear glass sphere under a uniform environment renders 1") {
  for (float n : {1.f, 1.5f, 2.42f}) {
    INFO("ior " << n);
    const auto img = render_glass_furnace(ConstantIor{n}, 1024);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, 1.0, 0.01);
  }
}

TEST_CASE("furnace: a dispersive glass sphere under a uniform environment renders 1") {
  // Dispersion terminates the companion wavelengths: unbiased, but noisier, hence more samples.
  const auto img = render_glass_furnace(AbbeIor{1.7f, 20.f}, 8192);
  CHECK(img.stats.invalid_samples == 0);
  test::check_mean(img, 0, 0, 16, 16, 1.0, 0.01);
}

TEST_CASE("Beer-Lambert: a slab transmits exp(-sigma_a d) straight on") {
  // An index-matched (n = 1) slab of thickness d = 0.5 and σ_a = 3 between the camera and a
  // uniform sky: nothing reflects, so the transmitted radiance is exactly T · L_sky per wavelength.
  for (const float sigma : {3.f, 1e-8f, 1e4f}) {
    Scene scene;
    scene.materials.push_back(glass(ConstantIor{1.f}, RgbUnboundedSpectrum(Rgb{sigma, sigma, sigma})));
    test::add_mesh(scene, test::make_quad({-5, -5, 0.25f}, {10, 0, 0}, {0, 10, 0}, 0));   // front, facing +z
    test::add_mesh(scene, test::make_quad({-5, -5, -0.25f}, {0, 10, 0}, {10, 0, 0}, 0));  // back, facing −z
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const World world(scene);
    PathOptions options;
    options.russian_roulette = false;
    Sampler sampler(1);
    for (float lambda_nm : {400.f, 550.f, 700.f}) {
      sampler.start_pixel_sample({0, 0}, 0);
      SampledWavelengths<1> lambda = SampledWavelengths<1>::sample(
          {(lambda_nm - kLambdaMin) / (kLambdaMax - kLambdaMin), 0.f}, WavelengthSampling::uniform);
      RayCounters counters;
      const auto L = path_radiance<1, true, true>(world, Ray{{0, 0, 3}, {0, 0, -1}, kInfinity}, lambda, sampler,
                                                  options, counters);
      const Spectrum& sigma_a = *scene.materials[0].dielectric()->interior.sigma_a;
      const double expected =
          std::exp(-double(evaluate(sigma_a, lambda[0])) * 0.5) * evaluate(*scene.environment, lambda[0]);
      INFO("sigma " << sigma << " lambda " << lambda[0]);
      CHECK(evaluate(sigma_a, lambda[0]) == Approx(sigma).epsilon(1e-4));
      CHECK(L[0] == Approx(expected).epsilon(1e-3).margin(1e-30));
      CHECK(std::isfinite(L[0]));
    }
  }
}

TEST_CASE("KHR_materials_volume: white light turns into attenuationColor at attenuationDistance") {
  // A closed index-matched slab exactly one attenuation distance thick in front of a white sky
  // reads the attenuation colour. Per-channel −ln(colour) upsampled read (0.876, 0.598, 0.294)
  // for (0.9, 0.6, 0.3); the colour upsampled as a transmittance reproduces it within 0.01.
  const Rgb color{0.9f, 0.6f, 0.3f};
  const float distance = 0.5f;
  Scene scene;
  scene.materials.push_back(glass(ConstantIor{1.f}, RgbAbsorptionSpectrum(color, distance)));
  test::add_mesh(scene, test::make_quad({-5, -5, 0.25f}, {10, 0, 0}, {0, 10, 0}, 0));   // front, facing +z
  test::add_mesh(scene, test::make_quad({-5, -5, -0.25f}, {0, 10, 0}, {10, 0, 0}, 0));  // back, facing −z
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  const auto img = test::render_rgb(scene, test::look_at({0, 0, 3}, {0, 0, 0}, 10.f), 16, 16, 512);
  CHECK(img.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": " << img.mean(c) << " ± " << img.standard_error(c, 0, 0, 16, 16));
    CHECK(img.standard_error(c, 0, 0, 16, 16) < 0.0025);
    CHECK(img.mean(c) == Approx(color[c]).margin(0.01));
  }
}

TEST_CASE("a dispersive interface keeps only the hero wavelength, a plain one keeps all") {
  Material flint = glass(MaterialCatalogue::standard().dielectric("N-SF11"));
  Material plain = glass(ConstantIor{1.5f});
  auto lambda = SampledWavelengths<4>::sample({0.2f, 0.3f});
  make_hero_bsdf(plain, {}, lambda, nullptr);
  CHECK_FALSE(lambda.secondary_terminated());
  make_hero_bsdf(flint, {}, lambda, nullptr);
  CHECK(lambda.secondary_terminated());
  // A plain glass inside a dispersive medium also sees a λ-dependent index ratio.
  auto lambda2 = SampledWavelengths<4>::sample({0.2f, 0.3f});
  make_hero_bsdf(plain, {}, lambda2, flint.dielectric());
  CHECK(lambda2.secondary_terminated());
}

TEST_CASE("the Whitted and path integrators agree on smooth Fresnel surfaces lit by a point light") {
  // A dark diffuse floor under a point light, a gold sphere and a glass sphere on it. The path
  // tracer also carries light from the floor via the spheres back to the floor, which Whitted's
  // model leaves out; with albedo 0.1 that term is about 0.3% of the image (measured: 0.6% at
  // albedo 0.2, as it scales with the albedo), inside the 1% tolerance below.
  Scene scene;
  scene.materials.push_back(test::diffuse({0.1f, 0.1f, 0.1f}, "floor"));
  scene.materials.push_back(
      Material{.name = "gold", .kind = PbrMaterial::metal_of(MaterialCatalogue::standard().metal("Au"))});
  scene.materials.push_back(glass(ConstantIor{1.5f}));
  test::add_mesh(scene, test::make_quad({-4, 0, 4}, {8, 0, 0}, {0, 0, -8}, 0));
  test::add_mesh(scene, test::make_icosphere({-0.6f, 0.5f, 0}, 0.5f, 3, 1));
  test::add_mesh(scene, test::make_icosphere({0.6f, 0.5f, 0.2f}, 0.5f, 3, 2));
  scene.point_lights.push_back({"lamp", {0.5f, 3, 2}, RgbIlluminantSpectrum(Rgb{20, 20, 20})});
  const auto camera = test::look_at({0, 1.6f, 3.5f}, {0, 0.4f, 0}, 40.f);
  const auto path = test::render_rgb(scene, camera, 32, 24, 512, 64);
  const auto whitted = test::render_rgb(scene, camera, 32, 24, 512, 64, 1, 0, IntegratorKind::whitted);
  CHECK(path.stats.invalid_samples == 0);
  CHECK(whitted.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    const auto d = test::mean_difference(path, whitted, c);
    INFO("channel " << c << ": path " << path.mean(c) << ", whitted " << whitted.mean(c) << ", difference "
                    << d.difference << " +- " << d.standard_error);
    REQUIRE(d.standard_error <= 0.0025 * whitted.mean(c));
    CHECK(std::abs(d.difference) <= 0.01 * whitted.mean(c));
  }
}

TEST_CASE("light sampling and BSDF sampling agree on light seen through rough transmission") {
  // A small lamp behind a rough glass pane (thin-walled and solid): light sampling must see it
  // through the transmission lobe, or NEE+MIS loses what BSDF sampling alone finds.
  for (const bool thin : {true, false}) {
    Scene scene;
    scene.materials.push_back(
        Material{.name = "pane", .kind = PbrMaterial::glass(Dielectric(ConstantIor{1.5f}, {}, thin), 0.3f)});
    Material lamp = test::diffuse({0, 0, 0}, "lamp");
    lamp.emission = RgbIlluminantSpectrum(Rgb{50, 50, 50});
    scene.materials.push_back(lamp);
    test::add_mesh(scene, test::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
    test::add_mesh(scene, test::make_quad({-0.1f, -0.1f, -0.5f}, {0.2f, 0, 0}, {0, 0.2f, 0}, 1));  // faces +z
    const auto camera = test::look_at({0, 0, 3}, {0, 0, 0}, 20.f);
    RenderOptions options;
    options.spp = 256;
    options.path.max_depth = 4;
    const auto mis = test::render_rgb(scene, camera, 24, 24, options);
    options.path.next_event = false;
    const auto bsdf_only = test::render_rgb(scene, camera, 24, 24, options);
    INFO((thin ? "thin-walled" : "solid"));
    CHECK(mis.stats.invalid_samples == 0);
    for (int c = 0; c < 3; ++c) {
      const auto d = test::mean_difference(mis, bsdf_only, c);
      CHECK(mis.mean(c) > 0.05);
      CHECK(std::abs(d.difference) < 4 * d.standard_error + 1e-3 * mis.mean(c));
    }
  }
}
