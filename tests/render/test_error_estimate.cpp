// The render's own error estimate against the true error, under the default (Owen-scrambled
// Sobol) sampler: on scenes whose answer is known exactly, on the default scene and on a shared
// asset (skipped without the shared assets, PRISM_SHARED_DIR) against a long reference render.
// The estimated relative RMSE must be within 20% of the true one (on the default scene as root mean
// squares over 16 renders), both of luminance and of the RGB image written (linear Rec.709, where
// the wavelengths' colour noise shows).

#include <catch2/catch.hpp>

#include "core/render/error_estimate.h"
#include "core/scene/gltf_loader.h"
#include "spectral/cie.h"
#include "spectral/color_pipeline.h"
#include "tests/support/sanitizers.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Film render_film(const Scene& scene, const CameraDesc& camera, int size, int spp, uint64_t seed, int max_depth = 64,
                 int wavelengths = kDefaultWavelengths) {
  const World world(scene);
  RenderOptions o;
  o.spp = spp;
  o.wavelengths = wavelengths;
  o.seed = seed;
  o.path.max_depth = max_depth;
  o.progress = false;
  return render(world, Camera(camera, size, size), o).state.film;
}

// The true value of a pixel's X, Y, Z (channel c), and the variance of that truth when the truth is
// itself a render (0 when it is exact).
struct Truth {
  std::function<double(size_t p, int c)> mean;
  std::function<double(size_t p, const std::array<double, 3>& w)> variance = [](size_t, const auto&) { return 0.0; };
};

const OutputChannels& rgb_channels() {
  static const OutputChannels m = ColorPipeline::standard().matrix_from_xyz(ColorPipeline::kDefaultOutput);
  return m;
}

double channel(const Xyz& v, int c) { return c == 0 ? v.x : c == 1 ? v.y : v.z; }

double dot(const std::array<double, 3>& w, const std::array<double, 3>& v) {
  return w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
}

// sqrt(mean (v − v_true)²) / mean v_true over the pixels and the channels given (each a linear
// combination of X, Y, Z), with the reference's own estimated variance taken out of the squared
// error when the truth is itself a render.
double true_rel_rmse(const Film& film, const Truth& truth, const std::vector<std::array<double, 3>>& channels) {
  double squared = 0, mean = 0;
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    const std::array<double, 3> value{film.mean(p, 0), film.mean(p, 1), film.mean(p, 2)},
        exact{truth.mean(p, 0), truth.mean(p, 1), truth.mean(p, 2)};
    for (const auto& w : channels) {
      squared += sqr(dot(w, value) - dot(w, exact)) - truth.variance(p, w);
      mean += dot(w, exact);
    }
  }
  const double n = double(film.pixel_count() * channels.size());
  return std::sqrt(squared / n) / (mean / n);
}

// The estimate against the truth, both as root mean squares over the renders given, of luminance
// and of RGB. A render of a scene with rare bright paths (the default scene's caustics and the
// prism's colours) has a true error that scatters widely from seed to seed, and so does any
// estimate from its own samples; what must hold is that the estimate is right on average, as
// tools/bench_error_estimate.py measures it over seeds.
void check_estimates(const std::vector<Film>& films, const Truth& truth) {
  double estimate = 0, true_error = 0, estimate_rgb = 0, true_error_rgb = 0;
  for (const Film& film : films) {
    const ErrorEstimate error(film, rgb_channels());
    const double t = true_rel_rmse(film, truth, {{0, 1, 0}}),
                 t_rgb = true_rel_rmse(film, truth, {rgb_channels().begin(), rgb_channels().end()});
    INFO("estimated relative RMSE " << error.rel_rmse() << ", true " << t << "; of RGB " << error.output_rel_rmse()
                                    << ", true " << t_rgb << "; calibration of s²/n (Y) " << error.calibration()[1]
                                    << " from " << error.replicated_pixels() << " pixels");
    CHECK(error.replicated_pixels() > 50);
    estimate += sqr(error.rel_rmse()), true_error += sqr(t);
    estimate_rgb += sqr(error.output_rel_rmse()), true_error_rgb += sqr(t_rgb);
  }
  const double n = double(films.size());
  estimate = std::sqrt(estimate / n), true_error = std::sqrt(true_error / n);
  estimate_rgb = std::sqrt(estimate_rgb / n), true_error_rgb = std::sqrt(true_error_rgb / n);
  INFO("over " << films.size() << " renders: estimated relative RMSE " << estimate << ", true " << true_error
               << "; of RGB " << estimate_rgb << ", true " << true_error_rgb);
  CHECK(true_error > 0.005);  // a real error to estimate, far above the tables' own accuracy
  CHECK(estimate == Approx(true_error).epsilon(0.2));
  CHECK(estimate_rgb == Approx(true_error_rgb).epsilon(0.2));
}

}  // namespace

TEST_CASE("error estimate: a grey sphere filling the image under a uniform sky (Y = albedo exactly)") {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.5f, 0.5f, 0.5f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  // The sphere subtends ±11.5°; a 12° field of view sees only the sphere. The sky, sampled by the
  // cosine about the normal, lights a diffuse surface with no noise but the colour noise of the
  // wavelengths: 4 per path (not 8) leave an error worth estimating.
  const Film film = render_film(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 48, 4, 11, 64, 4);
  const Xyz white = spectrum_to_xyz(RgbIlluminantSpectrum(Rgb{1, 1, 1}));  // D65's, Y = 1
  check_estimates({film}, {[&](size_t, int c) { return 0.5 * channel(white, c); }});
}

TEST_CASE("error estimate: inside a closed emitting sphere (Y = Le / (1 - albedo) exactly)") {
  const Scene scene = test::emitting_sphere_scene();
  const Film film = render_film(scene, test::look_at({0, 0, 0.3f}, {0, 0, -1}, 60.f), 48, 8, 12, 1000);
  const Xyz white = spectrum_to_xyz(RgbIlluminantSpectrum(Rgb{1, 1, 1}));  // Le / (1 − albedo) of D65's white
  check_estimates({film}, {[&](size_t, int c) { return channel(white, c); }});
}

// `renders` renders of spp samples (seeds 13, 14, ...) against one of 64 × spp (16 × spp under the
// sanitizers: the reference's own variance is subtracted from the true error, so a noisier one
// leaves it unbiased).
void check_against_reference(const Scene& scene, const CameraDesc& camera, int size, int spp, int renders) {
  const Film reference = render_film(scene, camera, size, 64 * spp / test::kSampleDivisor, 100);
  const ErrorEstimate reference_error(reference);
  std::vector<Film> films;
  for (int i = 0; i < renders; ++i) films.push_back(render_film(scene, camera, size, spp, 13 + i));
  check_estimates(films, {[&](size_t p, int c) { return reference.mean(p, c); },
                          [&](size_t p, const std::array<double, 3>& w) {
                            // The reference's variance of w · XYZ, calibrated as the renders' are
                            // (by Y's κ: its spread is luminance's; the estimate's own channel
                            // calibrations are what the test checks).
                            return reference_error.calibration()[1] * reference.variance_of_mean(p, w);
                          }});
}

TEST_CASE("error estimate: the default scene against a long reference") {
  const Scene scene = load_gltf(PRISM_SOURCE_DIR "/data/scenes/cornell.gltf");
  REQUIRE(!scene.cameras.empty());
  // 128² pixels, of which the one in 16 replicated (1,024) set the calibration: with the 256 of 64²
  // the estimate overstated this scene's true error by 1.2x (tools/bench_error_estimate.py found the
  // same below about a thousand pixels); 8 spp keep the cost of the 16 renders and the reference.
  check_against_reference(scene, scene.cameras[0], 128, 8, 16);
}

TEST_CASE("error estimate: a shared asset (Box under a uniform sky) against a long reference", "[shared]") {
  const auto file = test::shared_dir() / "assets/gltf/Box/glTF/Box.gltf";
  if (!test::shared_assets_present("assets/gltf/Box/glTF/Box.gltf")) return;
  Scene scene = load_gltf(file);
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  check_against_reference(scene, framing_camera(scene.world_bounds(), 1.f), 64, 16, 1);
}
