// Stiff and extreme cases (data/scenes/stress/, made by make_stress.py): every one renders with
// zero NaN/Inf samples and matches its analytic or well-conditioned reference within noise.

#include <catch2/catch.hpp>

#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Scene stress_scene(const std::string& name) {
  return load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/stress" / name);
}

test::TestRender render_stress(const Scene& scene, int size, int spp, uint64_t seed = 1) {
  const auto img = test::render_rgb(scene, scene.cameras.at(0), size, size, spp, 1000, seed);
  CHECK(img.stats.invalid_samples == 0);
  for (float v : img.rgb) REQUIRE(std::isfinite(v));
  return img;
}

}  // namespace

TEST_CASE("scale 1e-4 and 1e4, and geometry 1e5 from the origin, render like the unit-scale scene") {
  // Radiance is scale-invariant; far from the origin, ray offsets follow the coordinates'
  // magnitude, so no surface shadows or re-hits itself. Other seeds make the noise of the two
  // renders independent, as the test's tolerance assumes.
  const auto reference = render_stress(stress_scene("room.gltf"), 24, 256);
  for (const char* name : {"room_tiny.gltf", "room_huge.gltf", "room_far.gltf", "room_slivers.gltf"}) {
    const auto img = render_stress(stress_scene(name), 24, 256, 2);
    for (int c = 0; c < 3; ++c) {
      const auto d = test::mean_difference(img, reference, c);
      INFO(name << ", channel " << c << ": mean " << img.mean(c) << " vs " << reference.mean(c) << ", difference "
                << d.difference << " ± " << d.standard_error);
      REQUIRE(d.standard_error < 0.01 * reference.mean(c));
      CHECK(std::abs(d.difference) <= 4 * d.standard_error);
    }
  }
}

TEST_CASE("a tiny, very bright light gives the irradiance of a point source") {
  // 1 mm², 1e6 cd/m², 1 m above a Lambertian floor of albedo 0.8: E = L A h² / (h² + r²)².
  const Scene scene = stress_scene("tiny_bright_light.gltf");
  const auto img = render_stress(scene, 32, 1024);
  const double expected = 0.8 / kPi;  // at r ≈ 0 (the central pixels see r < 5 mm)
  test::check_mean(img, 12, 12, 20, 20, expected, 0.01 * expected);
}

TEST_CASE("indices of refraction 1, 1.0001, 4 and 10 neither create nor lose energy") {
  Scene scene = stress_scene("extreme_ior.gltf");
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  const auto img = render_stress(scene, 64, 512);
  // The four spheres' centres sit at x = −3.3, −1.1, 1.1, 3.3 at 12 units, 40° field of view.
  const double half_width = 12 * std::tan(radians(20.f));
  for (const double x : {-3.3, -1.1, 1.1, 3.3}) {
    const int px = int((x / half_width + 1) / 2 * 64);
    INFO("sphere at x = " << x);
    test::check_mean(img, px - 3, 29, px + 3, 35, 1.0, 0.02);
  }
}

TEST_CASE("absorption sigma_a d = 1e4 transmits nothing, 1e-8 everything, never NaN") {
  Scene scene = stress_scene("extreme_absorption.gltf");
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  const auto img = render_stress(scene, 48, 512);
  // Slabs centred at x = −0.75 and 0.75, 5 units away, 30° field of view.
  const double half_width = 5 * std::tan(radians(15.f));
  const int left = int((-0.75 / half_width + 1) / 2 * 48), right = int((0.75 / half_width + 1) / 2 * 48);
  for (int c = 0; c < 3; ++c) CHECK(img.mean(c, left - 3, 21, left + 3, 27) == 0.0);
  test::check_mean(img, right - 3, 21, right + 3, 27, 1.0, 0.02);
}

TEST_CASE("a conductor with k = 1000 is a perfect mirror") {
  Scene scene;
  scene.materials.push_back(
      Material{.name = "mirror",
               .kind = PbrMaterial::metal_of(MeasuredMetal{ConstantSpectrum{1.f}, ConstantSpectrum{1000.f}, "k1000"})});
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  const auto img = test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 16, 16, 1024, 64);
  CHECK(img.stats.invalid_samples == 0);
  test::check_mean(img, 0, 0, 16, 16, 1.0, 0.01);
}
