// Progressive rendering: passes, stops and resumes change nothing but the sample counts, bit for
// bit, at any thread count; the film's own error estimate matches the true error; adaptive
// sampling puts samples where the noise is without moving the image's mean.

#include <catch2/catch.hpp>
#include <cstring>
#include <map>

#include "core/render/adaptive_sampling.h"
#include "core/render/checkpoint.h"
#include "core/render/error_estimate.h"
#include "core/render/pass_schedule.h"
#include "core/scene/gltf_loader.h"
#include "materials/catalogue.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// A scene made ready to render, with its camera.
struct Setup {
  Scene scene;
  std::unique_ptr<World> world;
  std::unique_ptr<Camera> camera;

  Setup(Scene s, const CameraDesc& c, int width, int height)
      : scene(std::move(s)),
        world(std::make_unique<World>(scene)),
        camera(std::make_unique<Camera>(c, width, height)) {}

  RenderResult render(RenderOptions options, const RenderControl& control = {},
                      std::optional<RenderState> resume = {}) const {
    options.progress = false;
    return prism::render(*world, *camera, options, control, std::move(resume));
  }
};

// A glass sphere above a diffuse floor, lit by a small bright quad above it (a caustic on the
// floor) and a dim uniform sky that fills the top of the image (a flat background).
Setup caustic_scene(int width = 32, int height = 24) {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.8f, 0.8f, 0.8f}, "floor"));
  scene.materials.push_back(Material{.name = "glass", .kind = PbrMaterial::glass(Dielectric(ConstantIor{1.5f}))});
  Material lamp = test::diffuse({0, 0, 0}, "lamp");
  lamp.emission = RgbIlluminantSpectrum(Rgb{400, 400, 400});
  scene.materials.push_back(lamp);
  test::add_mesh(scene, test::make_quad({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 0));
  test::add_mesh(scene, test::make_icosphere({0, 0.9f, 0}, 0.5f, 3, 1));
  test::add_mesh(scene, test::make_quad({-0.1f, 3, -0.1f}, {0.2f, 0, 0}, {0, 0, 0.2f}, 2));
  scene.environment = RgbIlluminantSpectrum(Rgb{0.1f, 0.1f, 0.1f});
  return Setup(std::move(scene), test::look_at({0, 1.6f, 3.5f}, {0, 0.5f, 0}, 50.f), width, height);
}

// Every field of a film, as bytes: two films are the same render only if these are equal.
std::vector<char> film_bytes(const Film& film) {
  std::vector<char> bytes;
  film.visit_fields([&](const auto& v) {
    const char* p = reinterpret_cast<const char*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(v[0]));
  });
  film.visit_wide([&](size_t pixel, const Film::WideSums& w) {
    const auto add = [&](const void* p, size_t n) {
      bytes.insert(bytes.end(), static_cast<const char*>(p), static_cast<const char*>(p) + n);
    };
    add(&pixel, sizeof(pixel));
    for (const auto* field : {&w.sum, &w.sq, &w.cross, &w.second_sum, &w.splat})
      for (const WideSum& sum : *field) add(sum.words().data(), sizeof(sum.words()));
    for (const WideSum& sum : w.spectral) add(sum.words().data(), sizeof(sum.words()));
  });
  return bytes;
}

RenderOptions options_with(int spp, int threads, uint64_t seed = 3) {
  RenderOptions o;
  o.spp = spp;
  o.threads = threads;
  o.seed = seed;
  return o;
}

}  // namespace

TEST_CASE("a film given n equal samples at once holds what n single adds give, bit for bit") {
  // The renderer adds a pixel's camera samples that see the constant sky this way. Values beyond
  // the fixed-point range (3e9, 1e30) go to the pixel's wide sums, and count as valid.
  for (const Xyz xyz : {Xyz{0.3f, 0.7f, 1.9f}, Xyz{-2.5e-3f, 1e6f, 0.f}, Xyz{NAN, 1.f, 1.f}, Xyz{3e9f, 0.f, 0.f},
                        Xyz{1e30f, -3e38f, 0.5f}}) {
    Film one(3, 2, kAovAlbedo | kAovDepth), many(3, 2, kAovAlbedo | kAovDepth);
    for (Film* f : {&one, &many})
      f->add(4, FilmSample{{0.25f, 0.5f, 0.125f}, {0.5f, 0.5f, 0.5f}, {0, 0, 1}, 2.f, true});
    const bool valid = std::isfinite(xyz.x);
    for (int replicate = 0; replicate < 2; ++replicate) {
      for (int i = 0; i < 7; ++i) CHECK(one.add(4, FilmSample{xyz}, replicate) == valid);
      CHECK(many.add_repeated(4, Film::to_fixed_xyz(xyz), 7, replicate) == valid);
    }
    CHECK(film_bytes(one) == film_bytes(many));
    CHECK(many.samples(4) == 8);
    CHECK(many.second_replicate_samples(4) == 7);
  }
}

TEST_CASE("a film knows the variance of any linear combination of X, Y, Z: an output space's channels") {
  // Colour noise with a steady luminance: X and Z swing against each other, Y barely moves. The
  // Rec.709 red and blue channels see it where Y does not. One pixel also has samples beyond the
  // fixed-point range, whose products go to the wide sums.
  const OutputChannels rgb{
      {{3.2404542, -1.5371385, -0.4985314}, {-0.9692660, 1.8760108, 0.0415560}, {0.0556434, -0.2040259, 1.0572252}}};
  Film film(2, 1);
  std::vector<std::array<double, 3>> samples[2];
  for (int i = 0; i < 24; ++i) {
    const float swing = 0.3f * float((i * 7) % 11 - 5) / 5;
    const Xyz xyz{0.95f + swing, 1.f + 0.01f * float(i % 3), 1.09f - swing};
    for (int p = 0; p < 2; ++p) {
      const Xyz v = p == 0 ? xyz : xyz * (i % 4 == 0 ? 4e9f : 1.f);
      REQUIRE(film.add(p, FilmSample{v}, i % 2));
      samples[p].push_back({v.x, v.y, v.z});
    }
  }
  for (int p = 0; p < 2; ++p) {
    std::array<double, 3> mean{};
    for (int k = 0; k < 3; ++k) {
      double sum = 0, squares = 0;
      for (const auto& v : samples[p]) {
        const double c = rgb[k][0] * v[0] + rgb[k][1] * v[1] + rgb[k][2] * v[2];
        sum += c, squares += c * c;
      }
      const double n = double(samples[p].size()), variance = (squares - sum * sum / n) / (n - 1) / n;
      CHECK(film.variance_of_mean(p, rgb[k]) == Approx(variance).epsilon(1e-9));
      mean[k] = sum / n;
    }
    if (p == 1) continue;
    // Alone in its image, a pixel's adaptive error is its largest channel's standard error over
    // its mean; in RGB it is twice and more its error in XYZ.
    double expected = 0;
    for (int k = 0; k < 3; ++k) expected = std::max(expected, std::sqrt(film.variance_of_mean(p, rgb[k])) / mean[k]);
    const std::array<double, 3> xyz_mean{film.mean(p, 0), film.mean(p, 1), film.mean(p, 2)};
    CHECK(adaptive_error(film, p, xyz_mean, rgb) == Approx(expected).epsilon(1e-9));
    CHECK(adaptive_error(film, p, xyz_mean, rgb) > 2 * adaptive_error(film, p, xyz_mean));
  }
}

TEST_CASE("the pass schedule is fixed: 1, 2, 4, 8, 16, then every 16, cut at the total") {
  CHECK(pass_end(0, 100) == 1);
  CHECK(pass_end(3, 100) == 8);
  CHECK(pass_end(4, 100) == 16);
  CHECK(pass_end(5, 100) == 32);
  CHECK(pass_end(9, 100) == 96);
  CHECK(pass_end(10, 100) == 100);
  CHECK(pass_count(100) == 11);
  CHECK(pass_count(1) == 1);
  CHECK(pass_count(16) == 5);
  for (int spp : {1, 5, 16, 17, 64})
    for (int k = 0; k + 1 < pass_count(spp); ++k) CHECK(pass_end(k, spp) == pass_end(k, 1000));
}

TEST_CASE("progressive renders are the same bit for bit at 1 and 2 threads, with AOVs and spectral bins") {
  const Setup s = caustic_scene();
  RenderOptions o = options_with(20, 1);
  o.aovs = kAovAlbedo | kAovNormal | kAovDepth;
  o.spectral_bins = SpectralBins::uniform(8);
  const RenderResult one = s.render(o);
  o.threads = 2;
  const RenderResult two = s.render(o);
  CHECK(one.state.passes == pass_count(20));
  CHECK(film_bytes(one.state.film) == film_bytes(two.state.film));
  for (size_t p = 0; p < one.state.film.pixel_count(); ++p) REQUIRE(one.state.film.samples(p) == 20);
}

TEST_CASE("a render stopped after any pass, by request or time limit, equals the straight render of its samples") {
  const Setup s = caustic_scene();
  for (int threads : {1, 2}) {
    INFO(threads << " threads");
    // Stopped by request after the fourth pass (8 samples).
    std::atomic<bool> stop{false};
    RenderControl control{&stop, [&](const PassReport& pass, const RenderState&) { stop = pass.pass == 3; }};
    const RenderResult stopped = s.render(options_with(64, threads), control);
    CHECK(stopped.interrupted);
    CHECK(stopped.state.passes == 4);
    CHECK(film_bytes(stopped.state.film) == film_bytes(s.render(options_with(8, 3 - threads)).state.film));

    // A time limit every pass reaches stops after the first pass.
    RenderOptions limited = options_with(64, threads);
    limited.time_limit = 1e-9;
    const RenderResult timed = s.render(limited);
    CHECK(timed.timed_out);
    CHECK(timed.state.passes == 1);
    CHECK(film_bytes(timed.state.film) == film_bytes(s.render(options_with(1, 3 - threads)).state.film));
  }
}

TEST_CASE("a render resumed from a checkpoint file equals the uninterrupted render bit for bit") {
  const Setup s = caustic_scene();
  const auto file = test::temp_dir("checkpoint") / "state.checkpoint";
  for (int threads : {1, 2}) {
    INFO(threads << " threads");
    RenderOptions o = options_with(24, threads);
    o.aovs = kAovDepth;
    o.spectral_bins = SpectralBins::uniform(4);
    std::atomic<bool> stop{false};
    const RenderResult first =
        s.render(o, {&stop, [&](const PassReport& pass, const RenderState&) { stop = pass.pass == 2; }});
    REQUIRE(first.state.passes == 3);
    save_checkpoint(file, first.state, "fingerprint");
    CHECK_THROWS_WITH(load_checkpoint(file, "other"), Catch::Contains("another scene or other options"));
    const RenderResult resumed = s.render(o, {}, load_checkpoint(file, "fingerprint"));
    CHECK_FALSE(resumed.interrupted);
    uint64_t replicated = 0;  // pixels that take each sample index twice (error_estimate.h)
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 32; ++x) replicated += replicated_pixel({x, y}, o.seed);
    CHECK(replicated > 0);
    CHECK(resumed.state.stats.samples == uint64_t(24) * (32 * 24 + replicated));
    CHECK(film_bytes(resumed.state.film) == film_bytes(s.render(o).state.film));
  }
  // A damaged file fails with a clear message instead of resuming from garbage.
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 7);
  CHECK_THROWS_WITH(load_checkpoint(file, "fingerprint"), Catch::Contains("truncated or damaged"));
}

TEST_CASE("the time limit counts the seconds of the runs before a resume") {
  const Setup s = caustic_scene();
  RenderOptions o = options_with(64, 2);
  std::atomic<bool> stop{false};
  RenderResult first = s.render(o, {&stop, [&](const PassReport&, const RenderState&) { stop = true; }});
  REQUIRE(first.state.passes == 1);
  // The checkpoint says an hour went by; an hour's limit stops the resumed render after its first pass.
  first.state.stats.seconds = 3600;
  o.time_limit = 3600;
  const RenderResult resumed = s.render(o, {}, std::move(first.state));
  CHECK(resumed.timed_out);
  CHECK(resumed.state.passes == 2);
  CHECK(resumed.state.stats.seconds > 3600);
}

TEST_CASE("adaptive sampling: every pixel equals the straight render of its own sample count, at 1 and 2 threads") {
  const Setup s = caustic_scene();
  RenderOptions o = options_with(128, 1);
  o.noise_threshold = 0.1;
  const RenderResult adaptive = s.render(o);
  o.threads = 2;
  CHECK(film_bytes(s.render(o).state.film) == film_bytes(adaptive.state.film));
  const Film& film = adaptive.state.film;
  std::map<uint32_t, Film> straight;
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    const uint32_t n = film.samples(p);
    if (!straight.count(n)) straight.emplace(n, s.render(options_with(int(n), 2)).state.film);
    const Film& f = straight.at(n);
    REQUIRE(f.samples(p) == n);
    REQUIRE(f.mean_y(p) == film.mean_y(p));
    REQUIRE(f.variance_of_mean(p) == film.variance_of_mean(p));
    REQUIRE(f.xyz_image()[p * 3] == film.xyz_image()[p * 3]);
  }
  CHECK(straight.size() > 1);  // the pixels did not all take the same number of samples
}

TEST_CASE("adaptive sampling spends fewer samples on a flat background than on a caustic, keeping the mean") {
  const Setup s = caustic_scene(48, 36);
  const int max_spp = 256;
  RenderOptions o = options_with(max_spp, 0);
  const RenderResult uniform = s.render(o);
  o.noise_threshold = 0.05;
  const RenderResult adaptive = s.render(o);
  const Film &u = uniform.state.film, &a = adaptive.state.film;

  // Flat background: the top six rows, which see only the sky; noisy: the tenth of the pixels
  // with the largest variance in the uniform render (the caustic, the lit floor, the sphere's
  // refractions of them and of the lamp).
  std::vector<std::pair<double, size_t>> errors;
  double flat_spp = 0, noisy_spp = 0;
  int flat = 0;
  for (size_t p = 0; p < u.pixel_count(); ++p) {
    if (p < 6 * size_t(u.width())) {
      flat_spp += a.samples(p);
      ++flat;
    }
    errors.push_back({u.variance_of_mean(p), p});
  }
  std::sort(errors.rbegin(), errors.rend());
  const size_t noisy = errors.size() / 10;
  for (size_t i = 0; i < noisy; ++i) noisy_spp += a.samples(errors[i].second);
  REQUIRE(flat > 20);
  flat_spp /= flat;
  noisy_spp /= double(noisy);
  INFO("mean spp: flat background " << flat_spp << ", noisiest tenth " << noisy_spp);
  // The sky is flat but for the colour noise of its sampled wavelengths: it stops after a few
  // passes; the caustic never reaches the threshold and takes the maximum.
  CHECK(flat_spp < max_spp / 3);
  CHECK(noisy_spp > 0.95 * max_spp);
  CHECK(adaptive.stats().samples < 0.7 * uniform.stats().samples);

  // The image mean: the adaptive render stops pixels early, so it differs from the uniform one
  // by the noise of the samples it skipped, at most (a bias would show beyond that).
  double mean_u = 0, mean_a = 0, variance = 0;
  for (size_t p = 0; p < u.pixel_count(); ++p) {
    mean_u += u.mean_y(p);
    mean_a += a.mean_y(p);
    variance += a.variance_of_mean(p) + u.variance_of_mean(p);
  }
  const double n = double(u.pixel_count());
  INFO("mean Y uniform " << mean_u / n << ", adaptive " << mean_a / n << ", standard error "
                         << std::sqrt(variance) / n);
  CHECK(std::abs(mean_a - mean_u) / n < 4 * std::sqrt(variance) / n);
}
