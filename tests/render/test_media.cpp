// Participating media (materials/medium.h, core/render/medium_sampling.h) against answers known
// without the renderer: a medium that only scatters returns all the light a uniform environment
// sends in (a volume furnace); one that also absorbs returns what a random walk written here
// finds; a medium whose extinction varies tenfold across the spectrum gives the same image with
// one wavelength per path and with eight, and the walk's answer wavelength by wavelength; light
// sampled in fog agrees with light found by the phase function and the BSDFs alone.

#include <catch2/catch.hpp>
#include <cmath>

#include "core/base/error.h"
#include "core/base/rng.h"
#include "core/base/warp.h"
#include "spectral/cie.h"
#include "spectral/color_pipeline.h"
#include "tests/support/sanitizers.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// The closed box [lo, hi], faces wound counter-clockwise seen from outside.
Mesh make_box(uint32_t material, const Vec3f& lo = Vec3f(-1, -1, -1), const Vec3f& hi = Vec3f(1, 1, 1)) {
  Mesh mesh;
  mesh.name = "box";
  for (int i = 0; i < 8; ++i)
    mesh.positions.push_back(Vec3f(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z));
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      // The face's corners in order around it, then each triangle turned to face outwards.
      const int a = 1 << axis, b = 1 << ((axis + 1) % 3), c = 1 << ((axis + 2) % 3), base = side ? a : 0;
      const uint32_t q[4] = {uint32_t(base), uint32_t(base | b), uint32_t(base | b | c), uint32_t(base | c)};
      for (const auto& t : {std::array{q[0], q[1], q[2]}, std::array{q[0], q[2], q[3]}}) {
        const Vec3f n = cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
        const bool outwards = n[axis] * (side ? 1.f : -1.f) > 0;
        mesh.indices.insert(mesh.indices.end(), {t[0], outwards ? t[1] : t[2], outwards ? t[2] : t[1]});
      }
    }
  mesh.material = material;
  return mesh;
}

// A scene of one closed box [−1, 1]³ of a dielectric of index `ior` (1: its faces neither reflect
// nor bend light, and what comes out is the medium's doing alone) filled with `medium`, under a
// uniform environment of radiance 1.
Scene medium_box(Medium medium, float ior = 1.f) {
  Scene scene;
  scene.materials.push_back(
      Material{.name = "medium", .kind = PbrMaterial::glass(Dielectric(ConstantIor{ior}, std::move(medium)))});
  test::add_mesh(scene, make_box(0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  return scene;
}

// An orthographic camera above the box looking down −z at the square [−h, h]² of its top face.
CameraDesc looking_down(float h) {
  CameraDesc c = test::look_at({0, 0, 5}, {0, 0, 0}, 30.f);
  c.projection = CameraDesc::Projection::orthographic;
  c.xmag = c.ymag = h;
  return c;
}

Medium isotropic(float sigma_s, float sigma_a) {
  return Medium{.sigma_a = ConstantSpectrum{sigma_a}, .sigma_s = ConstantSpectrum{sigma_s}, .phase = {0.f}};
}

// Brute force, independent of the renderer: radiance leaving an index-matched box straight up at
// a point uniform in [−h, h]² of its top face z = 1, under a uniform environment of radiance 1, with
// isotropic scattering: the share of analog random walks (followed backwards, from the camera,
// absorbed at each scattering with probability 1 − σ_s/σ_t) that leave the box. The box is
// [−1, 1]³, or with `half_space` the half-space z < 1.
double walk_radiance(double sigma_s, double sigma_a, float h, int walks, Rng& rng, bool half_space = false) {
  const double sigma_t = sigma_s + sigma_a, albedo = sigma_s / sigma_t;
  int left = 0;
  for (int i = 0; i < walks; ++i) {
    Vec3f p((2 * rng.uniform() - 1) * h, (2 * rng.uniform() - 1) * h, 1.f), d(0, 0, -1);
    for (;;) {
      float exit = d.z > 0 ? (1 - p.z) / d.z : kInfinity;  // distance to the boundary along d
      if (!half_space)
        for (int a = 0; a < 3; ++a)
          if (d[a] != 0) exit = std::min(exit, ((d[a] > 0 ? 1.f : -1.f) - p[a]) / d[a]);
      const double t = -std::log(1 - double(rng.uniform())) / sigma_t;
      if (t >= exit) {
        ++left;
        break;
      }
      if (rng.uniform() >= albedo) break;  // absorbed
      p = p + d * float(t);
      d = sample_uniform_sphere({rng.uniform(), rng.uniform()});
    }
  }
  return double(left) / walks;
}

RenderOptions options(int spp, int wavelengths = kDefaultWavelengths, bool next_event = true) {
  RenderOptions o;
  o.spp = test::sanitized_samples(spp);
  o.seed = 3;
  o.wavelengths = wavelengths;
  o.path.max_depth = 1000;  // light may scatter many times before it leaves
  o.path.next_event = next_event;
  return o;
}

}  // namespace

TEST_CASE("volume furnace: a medium that only scatters, in glass or index-matched, returns all the light") {
  // Albedo 1: whatever the density, the asymmetry and the interface, every path leaves at last
  // with all its light, so the image is the environment's 1 everywhere, box or not.
  struct Case {
    float sigma_s, g, ior;
  };
  for (const Case c : {Case{0.5f, 0.f, 1.f}, Case{4.f, 0.8f, 1.f}, Case{4.f, -0.5f, 1.5f}, Case{1.f, 0.3f, 1.33f}}) {
    INFO("sigma_s " << c.sigma_s << " g " << c.g << " ior " << c.ior);
    const Scene scene = medium_box(Medium{.sigma_s = ConstantSpectrum{c.sigma_s}, .phase = {c.g}}, c.ior);
    const auto img = test::render_rgb(scene, looking_down(0.9f), 16, 16, options(256));
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, 1.0, 0.01 * test::kErrorScale);
  }
}

TEST_CASE("a medium that absorbs too returns what a random walk finds") {
  Rng rng(11, 0);
  for (const auto& [sigma_s, sigma_a] : {std::pair{1.4f, 0.6f}, std::pair{6.f, 0.3f}}) {
    INFO("sigma_s " << sigma_s << " sigma_a " << sigma_a);
    const double expected = walk_radiance(sigma_s, sigma_a, 0.5f, 400000, rng);
    REQUIRE(expected > 0.1);
    REQUIRE(expected < 0.9);
    const auto img =
        test::render_rgb(medium_box(isotropic(sigma_s, sigma_a)), looking_down(0.5f), 16, 16, options(256));
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, expected, 0.01 * test::kErrorScale);
  }
}

TEST_CASE(
    "a medium whose extinction varies tenfold with wavelength: one wavelength, eight, and a walk per wavelength "
    "agree") {
  // σ_t rises linearly from 0.3 at 360 nm to 3 at 830 nm, two thirds of it scattering: blue light
  // mostly crosses the box, red scatters many times and is absorbed, and the hero's distance
  // density differs up to tenfold from its companions'. Then a medium that leaves light below
  // 500 nm alone (σ_t = 0 there: such a hero never scatters, its companions must).
  const auto ramp = [](float at_360, float at_500, float at_830) {
    return Spectrum(TabulatedSpectrum({kLambdaMin, 500.f, kLambdaMax}, {at_360, at_500, at_830}));
  };
  const float tenfold_500 = 0.2f + (2.f - 0.2f) * (500 - kLambdaMin) / (kLambdaMax - kLambdaMin);
  for (const auto& [sigma_s, sigma_a] : {std::pair{ramp(0.2f, tenfold_500, 2.f), ramp(0.1f, tenfold_500 / 2, 1.f)},
                                         std::pair{ramp(0.f, 0.f, 2.f), ramp(0.f, 0.f, 1.f)}}) {
    INFO("sigma_s at 360 nm " << evaluate(sigma_s, kLambdaMin));
    const Medium medium{.sigma_a = sigma_a, .sigma_s = sigma_s, .phase = {0.f}};
    // The walk at every 5 nm, times the environment's spectrum, integrated against the CIE 1931
    // functions and converted as the film is.
    Rng rng(5, 0);
    std::vector<float> lambdas, walked, values;
    const Spectrum env = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    for (float l = kLambdaMin; l <= kLambdaMax; l += 5) {
      lambdas.push_back(l);
      walked.push_back(float(walk_radiance(evaluate(sigma_s, l), evaluate(sigma_a, l), 0.5f, 20000, rng)));
      values.push_back(walked.back() * evaluate(env, l));
    }
    CHECK(walked.back() < 0.6f * walked.front());  // the test sees a spectrum, not a grey
    const Xyz xyz = spectrum_to_xyz(TabulatedSpectrum(lambdas, values));
    float expected[3] = {xyz.x, xyz.y, xyz.z};
    ColorPipeline::standard().convert(ColorPipeline::kXyz, ColorPipeline::kDefaultOutput, expected, 1);
    const Scene scene = medium_box(medium);
    const auto one = test::render_rgb(scene, looking_down(0.5f), 8, 8, options(2048, 1));
    const auto eight = test::render_rgb(scene, looking_down(0.5f), 8, 8, options(512, 8));
    for (const auto* img : {&one, &eight}) {
      CHECK(img->stats.invalid_samples == 0);
      for (int c = 0; c < 3; ++c) {
        INFO((img == &one ? "one wavelength" : "eight wavelengths") << ", channel " << c);
        REQUIRE(img->standard_error(c, 0, 0, 8, 8) <= 0.004 * test::kErrorScale);
        CHECK(img->mean(c, 0, 0, 8, 8) == Approx(expected[c]).margin(0.015 * test::kErrorScale));
      }
    }
  }
}

TEST_CASE("in fog, light sampling agrees with light found by the phase function and the BSDFs alone") {
  // A white floor under a small square lamp, all in a chromatic fog: next-event estimation, with
  // the fog's transmittance on its shadow rays and MIS weights across the fog, against paths
  // that only find the lamp by chance. Both unbiased; they must agree within their noise.
  Scene scene;
  scene.materials.push_back(test::diffuse({0.8f, 0.8f, 0.8f}, "floor"));
  Material lamp = test::diffuse({0, 0, 0}, "lamp");
  lamp.emission = RgbIlluminantSpectrum(Rgb{20, 20, 20});
  scene.materials.push_back(lamp);
  test::add_mesh(scene, test::make_quad({-3, 0, -3}, {0, 0, 6}, {6, 0, 0}, 0));                 // faces +y
  test::add_mesh(scene, test::make_quad({-0.3f, 1.5f, -0.3f}, {0.6f, 0, 0}, {0, 0, 0.6f}, 1));  // faces −y
  scene.medium = Medium{.sigma_a = ConstantSpectrum{0.05f},
                        .sigma_s = TabulatedSpectrum({kLambdaMin, kLambdaMax}, {0.6f, 0.06f}),
                        .phase = {0.4f}};
  const auto camera = test::look_at({0, 1.2f, 3.5f}, {0, 0.5f, 0}, 50.f);
  const auto with = test::render_rgb(scene, camera, 24, 16, options(256));
  const auto without = test::render_rgb(scene, camera, 24, 16, options(4096, kDefaultWavelengths, false));
  CHECK(with.stats.invalid_samples == 0);
  CHECK(without.stats.invalid_samples == 0);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": with light sampling " << with.mean(c) << ", without " << without.mean(c));
    const auto d = test::mean_difference(with, without, c);
    CHECK(with.mean(c) > 0.05);
    CHECK(std::abs(d.difference) <= 4 * d.standard_error + 1e-3);
    CHECK(d.standard_error <= 0.02 * with.mean(c) * test::kErrorScale);
  }
}

TEST_CASE("in absorbing fog every integrator dims light as exp(-sigma_a d) over the whole path") {
  // A grey floor (albedo 0.5) 2 m under a point light of intensity 4, seen straight down from 3 m
  // above it: L = (0.5/π) (4/2²) e^{−σ_a (2 + 3)}, the fog taking its share on the light's way to
  // the floor (a shadow ray, or a light path) and on the way up to the camera.
  constexpr float sigma_a = 0.2f;
  Scene scene;
  scene.materials.push_back(Material{.name = "floor", .kind = DiffuseMaterial{ConstantSpectrum{0.5f}}});
  test::add_mesh(scene, test::make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 0));  // faces +y
  scene.point_lights.push_back(PointLight{"lamp", {0, 2, 0}, RgbIlluminantSpectrum(Rgb{4, 4, 4})});
  scene.medium = Medium{.sigma_a = ConstantSpectrum{sigma_a}};
  const CameraDesc camera = test::look_at({0, 3, 0}, {0, 0, 0}, 0.5f);  // sees 1 cm of floor: L varies < 1e-4 there
  const double expected = 0.5 / kPi * (4 / 4.0) * std::exp(-sigma_a * 5.0);
  for (const IntegratorKind kind :
       {IntegratorKind::path, IntegratorKind::whitted, IntegratorKind::bdpt, IntegratorKind::vcm}) {
    INFO("integrator " << integrator(kind).name);
    RenderOptions o = options(256);
    o.integrator = kind;
    const auto img = test::render_rgb(scene, camera, 4, 4, o);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 4, 4, expected, 0.02 * expected * test::kErrorScale);
  }
}

TEST_CASE("subsurface: a thick slab reflects what a random walk in a half-space finds, about its colour") {
  // The slab is 400 mean free paths deep and 2000 wide under a uniform environment: a half-space,
  // seen straight down. Its medium is medium_of_albedo's for a multiple-scattering albedo ρ_ms
  // (the subsurface colour); the walk uses the same single-scattering albedo, so the render must
  // match it, and the fit must give about ρ_ms back (Kulla and Conty fitted an average over
  // directions: seen straight on, a slab is up to 0.05 darker).
  for (const float rho_ms : {0.3f, 0.8f, 0.95f}) {
    INFO("multiple-scattering albedo " << rho_ms);
    const Medium medium = medium_of_albedo(ConstantSpectrum{10.f}, ConstantSpectrum{rho_ms}, 0.f);
    const double sigma_s = evaluate(*medium.sigma_s, 550), sigma_a = evaluate(*medium.sigma_a, 550);
    CHECK(sigma_s + sigma_a == Approx(10).epsilon(1e-5));
    Rng rng(17, 0);
    const double expected = walk_radiance(sigma_s, sigma_a, 0.5f, 100000, rng, true);
    CHECK(expected <= rho_ms);  // seen straight on, at most the colour and within 0.06 of it (0.25 for 0.3)
    CHECK(expected >= rho_ms - 0.06);
    Scene scene;
    scene.materials.push_back(
        Material{.name = "slab", .kind = PbrMaterial::glass(Dielectric(ConstantIor{1.f}, medium))});
    test::add_mesh(scene, make_box(0, {-100, -100, -39}, {100, 100, 1}));
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const auto img = test::render_rgb(scene, looking_down(0.5f), 16, 16, options(256));
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, expected, 0.012 * test::kErrorScale);
  }
}

TEST_CASE("subsurface under a glass surface conserves energy: albedo 1 returns the environment, less never more") {
  for (const float rho_ms : {1.f, 0.6f}) {
    INFO("multiple-scattering albedo " << rho_ms);
    const Medium medium = medium_of_albedo(ConstantSpectrum{20.f}, ConstantSpectrum{rho_ms}, 0.3f);
    Scene scene;
    scene.materials.push_back(
        Material{.name = "wax", .kind = PbrMaterial::glass(Dielectric(ConstantIor{1.4f}, medium), 0.3f)});
    test::add_mesh(scene, make_box(0));
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const auto img = test::render_rgb(scene, looking_down(0.9f), 16, 16, options(128));
    CHECK(img.stats.invalid_samples == 0);
    if (rho_ms == 1)
      test::check_mean(img, 0, 0, 16, 16, 1.0, 0.01 * test::kErrorScale);
    else
      for (int c = 0; c < 3; ++c) CHECK(img.mean(c) < 0.95);
  }
}

TEST_CASE("in absorbing fog, light traced onto the film and light gathered from the camera agree") {
  // A floor filling the view under a point light, in absorbing fog: light tracing reaches the
  // camera only by its connections through the fog, the path tracer by its shadow rays and camera
  // rays; both unbiased, they must agree within their noise. And light from infinitely far (a
  // directional light) crosses infinitely much fog, for every integrator.
  Scene scene;
  scene.materials.push_back(Material{.name = "floor", .kind = DiffuseMaterial{ConstantSpectrum{0.5f}}});
  test::add_mesh(scene, test::make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 0));  // faces +y
  scene.point_lights.push_back(PointLight{"lamp", {0, 1, 0}, RgbIlluminantSpectrum(Rgb{4, 4, 4})});
  scene.medium = Medium{.sigma_a = ConstantSpectrum{0.3f}};
  const CameraDesc camera = test::look_at({0, 2, 0.01f}, {0, 0, 0}, 60.f);
  RenderOptions o = options(64);
  const auto path = test::render_rgb(scene, camera, 16, 16, o);
  o.integrator = IntegratorKind::light;
  o.spp = test::sanitized_samples(256);
  const auto light = test::render_rgb(scene, camera, 16, 16, o);
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": path " << path.mean(c) << ", light tracing " << light.mean(c));
    const auto d = test::mean_difference(path, light, c);
    CHECK(std::abs(d.difference) <= 4 * d.standard_error + 1e-4);
    CHECK(d.standard_error <= 0.01 * path.mean(c) * test::kErrorScale);
  }
  scene.point_lights.clear();
  scene.directional_lights.push_back(DirectionalLight{"sun", {0, -1, 0}, RgbIlluminantSpectrum(Rgb{3, 3, 3})});
  for (const IntegratorKind kind : {IntegratorKind::path, IntegratorKind::bdpt, IntegratorKind::light}) {
    INFO("integrator " << integrator(kind).name);
    RenderOptions s = options(16);
    s.integrator = kind;
    CHECK(test::render_rgb(scene, camera, 8, 8, s).mean(1) == 0);
  }
}

TEST_CASE("integrators that do not render scattering media refuse the scene, naming the one that does") {
  const Scene scene = medium_box(isotropic(1, 0));
  for (const IntegratorKind kind :
       {IntegratorKind::whitted, IntegratorKind::bdpt, IntegratorKind::vcm, IntegratorKind::light}) {
    RenderOptions o = options(1);
    o.integrator = kind;
    CHECK_THROWS_WITH(test::render_rgb(scene, looking_down(0.5f), 4, 4, o),
                      Catch::Contains("does not render scattering media") && Catch::Contains("--integrator path"));
  }
  CHECK(choose_integrator(analyze_features(scene), false).kind == IntegratorKind::path);
}
