// Any finite radiance renders: emitters and lights of 1e9 to 1e30 give the image of a dim one
// scaled, in every integrator, and the film sums such samples exactly (fixed_point.h's WideSum),
// through merges and checkpoints.

#include <catch2/catch.hpp>
#include <cmath>

#include "core/render/checkpoint.h"
#include "core/render/fixed_point.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// Wide sums compare by value: the same integers, whatever the order of adding.
WideSum wide_sum(std::initializer_list<double> values) {
  WideSum s;
  for (double v : values) s.add(v);
  return s;
}

// An emissive quad of radiance `radiance` filling the view, and a Lambertian floor lit by a point
// light of intensity `intensity` seen beside it.
Scene bright_scene(float radiance, float intensity) {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.8f, 0.8f, 0.8f}, "floor"));
  Material lamp = test::diffuse({0, 0, 0}, "panel");
  lamp.emission = RgbIlluminantSpectrum(Rgb{radiance, radiance, radiance});
  scene.materials.push_back(lamp);
  test::add_mesh(scene, test::make_quad({-4, 0, 4}, {8, 0, 0}, {0, 0, -8}, 0));        // floor, y = 0, facing up
  test::add_mesh(scene, test::make_quad({-0.5f, 0.5f, -1}, {1, 0, 0}, {0, 1, 0}, 1));  // panel facing +z
  scene.point_lights.push_back(
      PointLight{"bulb", {1.5f, 1, 0}, RgbIlluminantSpectrum(Rgb{intensity, intensity, intensity})});
  return scene;
}

}  // namespace

TEST_CASE("wide sums are exact: any grouping and order of the same values gives the same integers") {
  const double big = 3.0e38, huge_square = big * big;
  const WideSum a = wide_sum({3e9, 1e20, -7e25, big, huge_square, 5e9});
  const WideSum b = wide_sum({huge_square, 5e9, big, 3e9, -7e25, 1e20});
  CHECK(a == b);
  WideSum c = wide_sum({3e9, 1e20, -7e25});
  c += wide_sum({big, huge_square, 5e9});
  CHECK(c == a);
  // Integers below 2^53 add exactly, and `times` adds a value that many times.
  WideSum d;
  d.add(3e9, 1000);
  d.add(-1e9);
  CHECK(d.to_double() == 3e12 - 1e9);
  WideSum e;
  for (int i = 0; i < 1000; ++i) e.add(huge_square);
  WideSum f;
  f.add(huge_square, 1000);
  CHECK(e == f);
  CHECK(f.to_double() == Approx(1000 * huge_square).epsilon(1e-15));
  // A value and its negation cancel to zero exactly.
  CHECK(wide_sum({big, -big, 7e30, -7e30}) == WideSum{});
}

TEST_CASE("a film keeps samples beyond the fixed-point range exactly, through merges and checkpoints") {
  const float values[] = {1.f, 3e9f, 1e20f, 1e30f, 2.5e38f};
  Film whole(4, 2), first(4, 2), second(4, 2);
  for (int i = 0; i < 5; ++i) {
    const Xyz xyz{values[i], 0.5f * values[i], 1.f};
    for (int replicate = 0; replicate < 2; ++replicate) {
      REQUIRE(whole.add(5, FilmSample{xyz}, replicate));
      REQUIRE((i < 2 ? first : second).add(5, FilmSample{xyz}, replicate));
    }
  }
  const double expected = (1.0 + 3e9 + 1e20 + 1e30 + double(2.5e38f)) / 5;
  CHECK(whole.mean(5, 0) == Approx(expected).epsilon(1e-12));
  CHECK(whole.mean(5, 1) == Approx(0.5 * expected).epsilon(1e-12));
  CHECK(whole.mean(5, 2) == 1.0);
  CHECK(whole.replicate_mean(5, 0, 1) == Approx(expected).epsilon(1e-12));
  CHECK(std::isfinite(whole.variance_of_mean(5, 0)));
  CHECK(whole.variance_of_mean(5, 0) > 0);
  const std::vector<float> image = whole.xyz_image();
  CHECK(image[5 * 3] == float(whole.mean(5, 0)));
  // Parts merge to the whole, and a checkpoint keeps it.
  first.merge(second);
  CHECK(first.xyz_image() == image);
  CHECK(first.variance_of_mean(5, 0) == whole.variance_of_mean(5, 0));
  const auto file = test::temp_dir("wide_checkpoint") / "film.checkpoint";
  RenderState state{std::move(whole)};
  state.part = {0, 1, 1, {}};
  save_checkpoint(file, state, "wide");
  const RenderState loaded = load_render_state(file);
  CHECK(loaded.film.xyz_image() == image);
  CHECK(loaded.film.variance_of_mean(5, 0) == state.film.variance_of_mean(5, 0));
  CHECK(loaded.film.replicate_mean(5, 0, 1) == state.film.replicate_mean(5, 0, 1));
}

TEST_CASE("emitters and lights of 1e9 to 1e30 render as a dim one scaled, in every integrator") {
  const CameraDesc camera = test::look_at({0, 1.2f, 3}, {0, 0.5f, 0}, 60.f);
  for (const IntegratorKind integrator : {IntegratorKind::path, IntegratorKind::bdpt, IntegratorKind::vcm}) {
    const auto reference = test::render_rgb(bright_scene(1, 1), camera, 24, 16, 4, 8, 1, 0, integrator);
    REQUIRE(reference.stats.invalid_samples == 0);
    REQUIRE(reference.mean(1) > 0);
    for (const float scale : {1e9f, 1e12f, 1e20f, 1e30f}) {
      INFO("integrator " << int(integrator) << ", emitter and light scaled by " << scale);
      const auto img = test::render_rgb(bright_scene(scale, scale), camera, 24, 16, 4, 8, 1, 0, integrator);
      CHECK(img.stats.invalid_samples == 0);
      size_t differing = 0;
      for (size_t i = 0; i < img.rgb.size(); ++i) {
        REQUIRE(std::isfinite(img.rgb[i]));
        // The same paths, their radiance scaled: equal to float rounding (relative 1e-5 leaves
        // room for the products' rounding; a dropped or clipped sample differs by far more).
        if (std::abs(img.rgb[i] / scale - reference.rgb[i]) > 1e-5 * std::abs(reference.rgb[i]) + 1e-30) ++differing;
      }
      CHECK(differing == 0);
    }
  }
}
