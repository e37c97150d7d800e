// Bidirectional path tracing (core/render/bdpt.h) and vertex connection and merging (vcm.h)
// against scenes of known answer and against the path tracer on scenes it renders well (no
// caustics); light tracing alone (the t = 1 strategy) against the analytic irradiance of a point
// and of an area light; determinism across thread counts; no NaN or Inf on the stress scenes and
// the caustic report scenes; the wavelengths each integrator keeps after a dispersive interface.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "core/base/log.h"
#include "core/render/error_estimate.h"
#include "core/scene/gltf_loader.h"
#include "materials/catalogue.h"
#include "tests/support/sanitizers.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// Every channel of a and b (independent renders) agrees in the mean within 4 standard errors,
// which must themselves be below `precision` of b's mean.
void check_agree(const test::TestRender& a, const test::TestRender& b, double precision) {
  for (int c = 0; c < 3; ++c) {
    const auto d = test::mean_difference(a, b, c);
    INFO("channel " << c << ": mean " << a.mean(c) << " vs " << b.mean(c) << ", difference " << d.difference << " ± "
                    << d.standard_error);
    REQUIRE(d.standard_error < precision * b.mean(c));
    CHECK(std::abs(d.difference) <= 4 * d.standard_error);
  }
}

// The default scene with its metal and glass made white diffuse: no caustics.
Scene walls_only_cornell() {
  Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/cornell.gltf");
  for (Material& m : scene.materials)
    if (!m.emission && m.name != "white" && m.name != "red" && m.name != "green")
      m = test::diffuse({0.7f, 0.7f, 0.7f}, m.name);
  return scene;
}

Material glass(IorModel ior) {
  return Material{.name = "glass", .kind = PbrMaterial::glass(Dielectric(std::move(ior)))};
}

// An orthographic camera at height h looking straight down at the square [−s, s]² of y = 0
// (pixel (i, j) covers x = −s + [i, i + 1]·2s/n, z = −s + [j, j + 1]·2s/n).
CameraDesc looking_down(float h, float s) {
  CameraDesc camera;
  camera.projection = CameraDesc::Projection::orthographic;
  camera.xmag = camera.ymag = s;
  const Vec3f eye(0, h, 0), right(1, 0, 0), up(0, 0, -1), back(0, 1, 0);
  for (int r = 0; r < 3; ++r) {
    camera.to_world.m[r][0] = right[r];
    camera.to_world.m[r][1] = up[r];
    camera.to_world.m[r][2] = back[r];
    camera.to_world.m[r][3] = eye[r];
  }
  return camera;
}

}  // namespace

const IntegratorKind kBidirectional[] = {IntegratorKind::bdpt, IntegratorKind::vcm};

TEST_CASE("bdpt, vcm: a sphere of albedo 0.5 under a uniform environment of radiance 1 renders 0.5") {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.5f, 0.5f, 0.5f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  for (const IntegratorKind integrator : kBidirectional) {
    INFO((integrator == IntegratorKind::bdpt ? "bdpt" : "vcm"));
    const auto img =
        test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 30.f), 32, 32, 256, 64, 1, 0, integrator);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 10, 10, 22, 22, 0.5, 0.02);
    test::check_mean(img, 0, 0, 32, 3, 1.0, 0.02);  // top rows: sky
  }
}

TEST_CASE("bdpt, vcm: inside a closed emitting sphere the radiance is Le / (1 - albedo)") {
  const Scene scene = test::emitting_sphere_scene();
  for (const IntegratorKind integrator : kBidirectional) {
    INFO((integrator == IntegratorKind::bdpt ? "bdpt" : "vcm"));
    const auto img =
        test::render_rgb(scene, test::look_at({0, 0, 0.3f}, {0, 0, -1}, 60.f), 32, 32, 64, 1000, 1, 0, integrator);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 32, 32, 1.0, 0.02);
  }
}

TEST_CASE("light tracing alone reproduces a point light's irradiance on a plane, rho I cos / (pi d^2)") {
  // A 2 × 2 Lambertian square under a point light, filling the view of an orthographic camera
  // straight above (pixel (i, j) covers x = −1 + [i, i + 1]·2/n, z = −1 + [j, j + 1]·2/n): every
  // light path that reaches the square lands on the film.
  constexpr float kAlbedo = 0.5f, kIntensity = 4.f;
  const Vec3f light(0.3f, 1.f, -0.2f);
  Scene scene;
  scene.materials.push_back(test::diffuse({kAlbedo, kAlbedo, kAlbedo}));
  test::add_mesh(scene, test::make_quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0));
  scene.point_lights.push_back({"lamp", light, RgbIlluminantSpectrum(Rgb{kIntensity, kIntensity, kIntensity})});
  const CameraDesc camera = looking_down(4, 1);
  constexpr int n = 16;
  for (const IntegratorKind integrator : {IntegratorKind::light, IntegratorKind::bdpt}) {
    INFO((integrator == IntegratorKind::light ? "light tracing" : "bdpt"));
    test::TestRender r = test::render_rgb(scene, camera, n, n, 2048, 1, 1, 0, integrator);
    CHECK(r.stats.invalid_samples == 0);
    // Pixel by pixel divided by the expected radiance (E averaged over 8 × 8 points of the pixel).
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        double E = 0;
        for (int i = 0; i < 8; ++i)
          for (int j = 0; j < 8; ++j) {
            const Vec3d p(-1 + 2 * (x + (i + 0.5) / 8) / n, 0, -1 + 2 * (y + (j + 0.5) / 8) / n);
            const Vec3d d = Vec3d(light) - p;
            E += kIntensity * d.y / (length(d) * length_squared(d));
          }
        const double expected = kAlbedo * (E / 64) / kPi;
        for (int c = 0; c < 3; ++c) r.rgb[(size_t(y) * n + x) * 3 + c] /= float(expected);
      }
    test::check_mean(r, 0, 0, n, n, 1.0, 0.02);
    test::check_mean(r, 0, 0, n / 2, n / 2, 1.0, 0.04);  // a quadrant: the splats land where they belong
  }
}

TEST_CASE("light tracing alone reproduces an area light's irradiance on a plane, Lambert's polygon formula") {
  // A 0.5 × 0.5 square emitter of radiance L facing down at height 0.6, off the view's centre,
  // over the 2 × 2 Lambertian square of the point-light test; the orthographic camera sits at
  // 0.3, under the light, which it therefore does not see. Irradiance from a polygon of uniform
  // radiance (Lambert 1760): E(p) = L/2 · |Σ_i β_i n·γ_i|, β_i the angle edge i subtends at p and
  // γ_i the unit normal of the plane through p and that edge.
  constexpr float kAlbedo = 0.5f, kRadiance = 2.f;
  const Vec3d corners[] = {{0, 0.6, -0.2}, {0.5, 0.6, -0.2}, {0.5, 0.6, 0.3}, {0, 0.6, 0.3}};
  Scene scene;
  scene.materials.push_back(test::diffuse({kAlbedo, kAlbedo, kAlbedo}));
  Material lamp = test::diffuse({0, 0, 0}, "lamp");
  lamp.emission = RgbIlluminantSpectrum(Rgb{kRadiance, kRadiance, kRadiance});
  scene.materials.push_back(lamp);
  test::add_mesh(scene, test::make_quad({-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, 0));
  test::add_mesh(scene, test::make_quad(Vec3f(corners[0]), {0.5f, 0, 0}, {0, 0, 0.5f}, 1));  // front −Y
  const auto irradiance = [&](const Vec3d& p) {
    double sum = 0;
    for (int i = 0; i < 4; ++i) {
      const Vec3d a = normalize(corners[i] - p), b = normalize(corners[(i + 1) % 4] - p);
      sum += std::acos(std::clamp(dot(a, b), -1.0, 1.0)) * normalize(cross(a, b)).y;
    }
    return kRadiance / 2 * std::abs(sum);
  };
  const CameraDesc camera = looking_down(0.3f, 1);
  constexpr int n = 16;
  for (const IntegratorKind integrator : {IntegratorKind::light, IntegratorKind::bdpt}) {
    INFO((integrator == IntegratorKind::light ? "light tracing" : "bdpt"));
    test::TestRender r = test::render_rgb(scene, camera, n, n, 1024, 1, 1, 0, integrator);
    CHECK(r.stats.invalid_samples == 0);
    // Pixel by pixel divided by the expected radiance (E averaged over 8 × 8 points of the pixel).
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        double E = 0;
        for (int i = 0; i < 8; ++i)
          for (int j = 0; j < 8; ++j)
            E += irradiance(Vec3d(-1 + 2 * (x + (i + 0.5) / 8) / n, 0, -1 + 2 * (y + (j + 0.5) / 8) / n));
        const double expected = kAlbedo * (E / 64) / kPi;
        for (int c = 0; c < 3; ++c) r.rgb[(size_t(y) * n + x) * 3 + c] /= float(expected);
      }
    test::check_mean(r, 0, 0, n, n, 1.0, 0.02);
    test::check_mean(r, 0, 0, n / 2, n / 2, 1.0, 0.04);  // a quadrant: the splats land where they belong
  }
}

TEST_CASE("bdpt and light tracing agree with the path tracer on the default scene without metal and glass") {
  const Scene scene = walls_only_cornell();
  const CameraDesc& camera = scene.cameras.at(0);
  const auto path = test::render_rgb(scene, camera, 24, 24, 256, 16, 1);
  const auto bdpt = test::render_rgb(scene, camera, 24, 24, 128, 16, 2, 0, IntegratorKind::bdpt);
  CHECK(bdpt.stats.invalid_samples == 0);
  check_agree(bdpt, path, 0.02);
  const auto light = test::render_rgb(scene, camera, 24, 24, 128, 16, 3, 0, IntegratorKind::light);
  check_agree(light, path, 0.05);
  const auto vcm = test::render_rgb(scene, camera, 24, 24, 128, 16, 4, 0, IntegratorKind::vcm);
  CHECK(vcm.stats.invalid_samples == 0);
  check_agree(vcm, path, 0.02);
}

TEST_CASE("bdpt agrees with the path tracer on a point-lit diffuse scene with an environment") {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.7f, 0.4f, 0.2f}));
  scene.materials.push_back(test::diffuse({0.5f, 0.5f, 0.5f}, "floor"));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 2, 0));
  test::add_mesh(scene, test::make_quad({-4, -1, -4}, {0, 0, 8}, {8, 0, 0}, 1));
  scene.point_lights.push_back({"lamp", {2, 2, 2}, RgbIlluminantSpectrum(Rgb{10, 10, 10})});
  scene.environment = RgbIlluminantSpectrum(Rgb{0.2f, 0.3f, 0.5f});
  const auto camera = test::look_at({0, 1, 4}, {0, 0, 0}, 50.f);
  const auto path = test::render_rgb(scene, camera, 24, 24, 256, 16, 1);
  const auto bdpt = test::render_rgb(scene, camera, 24, 24, 128, 16, 2, 0, IntegratorKind::bdpt);
  CHECK(bdpt.stats.invalid_samples == 0);
  check_agree(bdpt, path, 0.02);
}

TEST_CASE("bdpt and vcm images, splats and photons included, are identical at 1 and 2 threads") {
  const Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/cornell.gltf");
  const CameraDesc& camera = scene.cameras.at(0);
  for (const IntegratorKind integrator : {IntegratorKind::bdpt, IntegratorKind::vcm}) {
    const auto one = test::render_rgb(scene, camera, 24, 24, 4, 16, 7, 1, integrator);
    const auto two = test::render_rgb(scene, camera, 24, 24, 4, 16, 7, 2, integrator);
    CHECK(one.rgb == two.rgb);
    CHECK(one.mean(1) > 0);
  }
}

TEST_CASE("bdpt and vcm render the stress scenes and the caustic report scenes with no NaN or Inf") {
  log::set_level(log::Level::quiet);
  const std::filesystem::path dir(PRISM_SOURCE_DIR "/data/scenes");
  for (const auto& file :
       {dir / "dispersion.gltf", dir / "prism_rainbow.gltf", dir / "glass_of_water.gltf", dir / "diamond.gltf",
        dir / "cornell.gltf", dir / "stress/extreme_absorption.gltf", dir / "stress/extreme_ior.gltf",
        dir / "stress/room_tiny.gltf", dir / "stress/room_huge.gltf", dir / "stress/room_far.gltf",
        dir / "stress/room_slivers.gltf", dir / "stress/tiny_bright_light.gltf"}) {
    INFO(file.string());
    Scene scene = load_gltf(file);
    if (scene.point_lights.empty() && !scene.environment) scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    for (const IntegratorKind integrator : {IntegratorKind::bdpt, IntegratorKind::vcm}) {
      const auto img = test::render_rgb(scene, scene.cameras.at(0), 16, 16, 8, 1000, 1, 0, integrator);
      CHECK(img.stats.invalid_samples == 0);
      for (float v : img.rgb) REQUIRE(std::isfinite(v));
    }
  }
  log::set_level(log::Level::info);
}

TEST_CASE("a caustic of known power: sunlight through a glass slab lights the floor with E (1 - R) / (1 + R)") {
  // Straight down through a slab of index 1.5 (R = 0.04 at each face, all internal reflections
  // summed) onto a floor of albedo 0.5, seen from under the slab. Light → specular → specular →
  // diffuse → camera: the path tracer never finds it (the sun is a delta light); light paths do.
  constexpr float kAlbedo = 0.5f, kE = 3.f;
  Scene scene;
  scene.materials.push_back(test::diffuse({kAlbedo, kAlbedo, kAlbedo}));
  scene.materials.push_back(glass(ConstantIor{1.5f}));
  // The floor and the slab 3 × 3, the view the central 2 × 2: all its light came through the slab.
  test::add_mesh(scene, test::make_quad({-1.5f, 0, -1.5f}, {0, 0, 3}, {3, 0, 0}, 0));     // floor, front +Y
  test::add_mesh(scene, test::make_quad({-1.5f, 1.2f, -1.5f}, {0, 0, 3}, {3, 0, 0}, 1));  // slab top, front +Y
  test::add_mesh(scene, test::make_quad({-1.5f, 1, -1.5f}, {3, 0, 0}, {0, 0, 3}, 1));     // slab bottom, front −Y
  scene.directional_lights.push_back({"sun", {0, -1, 0}, RgbIlluminantSpectrum(Rgb{kE, kE, kE})});
  const double R = 0.04, expected = kAlbedo / kPi * kE * (1 - R) / (1 + R);
  for (const IntegratorKind integrator : kBidirectional) {
    INFO((integrator == IntegratorKind::bdpt ? "bdpt" : "vcm"));
    const auto img = test::render_rgb(scene, looking_down(0.5f, 1), 16, 16, 1024, 16, 1, 0, integrator);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, expected, 0.02 * expected);
  }
}

TEST_CASE("bdpt, vcm: a dispersive glass sphere under a uniform environment renders 1") {
  Scene scene;
  scene.materials.push_back(glass(AbbeIor{1.7f, 20.f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
  for (const IntegratorKind integrator : kBidirectional) {
    INFO((integrator == IntegratorKind::bdpt ? "bdpt" : "vcm"));
    const auto img =
        test::render_rgb(scene, test::look_at({0, 0, 5.f}, {0, 0, 0}, 12.f), 16, 16, 2048, 1000, 1, 0, integrator);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, 1.0, 0.02);
  }
}

TEST_CASE("bdpt, vcm and the path tracer agree on the dispersive prism in mean and colour") {
  Scene scene = load_gltf(std::filesystem::path(PRISM_SOURCE_DIR) / "data/scenes/dispersion.gltf");
  const CameraDesc& camera = scene.cameras.at(0);
  const auto path = test::render_rgb(scene, camera, 24, 24, test::sanitized_samples(4096), 16, 1);
  for (const IntegratorKind integrator : kBidirectional) {
    INFO((integrator == IntegratorKind::bdpt ? "bdpt" : "vcm"));
    const auto img = test::render_rgb(scene, camera, 24, 24, test::sanitized_samples(1024), 16, 2, 0, integrator);
    CHECK(img.stats.invalid_samples == 0);
    check_agree(img, path, 0.03 * test::kErrorScale);
  }
}

TEST_CASE("bdpt, vcm: a light path through a dispersive sphere leaves the directly seen light all its wavelengths") {
  // The camera sees only a black emitter; a dispersive glass sphere beside it, out of view, is
  // where many light paths go. Every contribution but the emitter's own is zero, so the pixels
  // must be the path tracer's (bdpt: same sampler streams) or all alike (vcm: an iteration's
  // wavelengths are the whole image's), as they were not while a light path through the sphere
  // made its whole sample hero-only.
  Scene scene;
  Material light{.name = "black emitter", .kind = DiffuseMaterial{ConstantSpectrum{0.f}}};
  light.emission = RgbIlluminantSpectrum(Rgb{1.f, 0.7f, 0.4f});
  scene.materials.push_back(light);
  scene.materials.push_back(glass(AbbeIor{1.7f, 20.f}));
  test::add_mesh(scene, test::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
  test::add_mesh(scene, test::make_icosphere({2.5f, 0, 1.5f}, 1.f, 3, 1));
  const CameraDesc camera = test::look_at({0, 0, 3}, {0, 0, 0}, 20.f);
  const auto path = test::render_rgb(scene, camera, 16, 16, 16, 16, 1);
  const auto bdpt = test::render_rgb(scene, camera, 16, 16, 16, 16, 1, 0, IntegratorKind::bdpt);
  const auto vcm = test::render_rgb(scene, camera, 16, 16, 16, 16, 1, 0, IntegratorKind::vcm);
  CHECK(bdpt.stats.rays.secondary > 0);  // light paths were traced
  for (size_t i = 0; i < path.rgb.size(); ++i) {
    INFO("value " << i << ": path " << path.rgb[i] << ", bdpt " << bdpt.rgb[i] << ", vcm " << vcm.rgb[i]);
    REQUIRE(path.rgb[i] > 0.f);
    // (The path tracer takes a second, independent set of samples in its error estimate's pixels.)
    const int x = int(i / 3 % 16), y = int(i / 3 / 16);
    if (!replicated_pixel({x, y}, 1)) CHECK(bdpt.rgb[i] == Approx(path.rgb[i]).epsilon(1e-5));
    CHECK(vcm.rgb[i] == Approx(vcm.rgb[i % 3]).epsilon(1e-5));
  }
}

TEST_CASE("path tracer: the light a path saw before a dispersive interface keeps all its wavelengths") {
  // An emitting glass quad alone in the dark: the camera sees its emission, then the path goes on
  // into the glass and out into nothing. A dispersive index must give the pixels of a constant
  // one bit for bit, as it did not while meeting the dispersive surface made the whole sample
  // hero-only.
  const auto render = [](IorModel ior) {
    Scene scene;
    Material emitter = glass(std::move(ior));
    emitter.emission = RgbIlluminantSpectrum(Rgb{1.f, 0.7f, 0.4f});
    scene.materials.push_back(emitter);
    test::add_mesh(scene, test::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
    return test::render_rgb(scene, test::look_at({0, 0, 3}, {0, 0, 0}, 20.f), 16, 16, 16, 16, 1);
  };
  const auto dispersive = render(AbbeIor{1.7f, 20.f}), constant = render(ConstantIor{1.7f});
  for (size_t i = 0; i < constant.rgb.size(); ++i) {
    INFO("value " << i << ": dispersive " << dispersive.rgb[i] << ", constant " << constant.rgb[i]);
    REQUIRE(constant.rgb[i] > 0.f);
    CHECK(dispersive.rgb[i] == Approx(constant.rgb[i]).epsilon(1e-6));
  }
}
