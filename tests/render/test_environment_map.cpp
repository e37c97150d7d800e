// Environment maps: the lat-long mapping and its rotation, an importance-sampling pdf that
// integrates to 1 and matches its samples (χ²), radiometry against analytic irradiance (a
// constant map is the constant environment; a bright block of texels lights a plane with the
// irradiance of its solid angle), and loading .exr and .hdr files.

#include <stb_image_write.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <functional>

#include "core/base/rng.h"
#include "core/render/environment_map.h"
#include "core/render/image_output.h"
#include "tests/support/chi2.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

EnvironmentMapDesc make_map(int width, int height, const std::function<Rgb(int x, int y)>& texel, float rotation = 0,
                            float scale = 1) {
  EnvironmentMapDesc d{"test map", {width, height, {}}, rotation, scale, 0, std::nullopt};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgb c = texel(x, y);
      d.image.rgb.insert(d.image.rgb.end(), {c.r, c.g, c.b});
    }
  return d;
}

// 0 except a block of texels [x0, x1) × [y0, y1) of grey radiance L.
EnvironmentMapDesc block_map(int x0, int y0, int x1, int y1, float L, float rotation = 0) {
  return make_map(
      64, 32,
      [=](int x, int y) {
        return x >= x0 && x < x1 && y >= y0 && y < y1 ? Rgb{L, L, L} : Rgb{};
      },
      rotation);
}

void check_near(const Vec3f& a, const Vec3f& b) {
  INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")");
  CHECK(length(a - b) < 1e-5f);
}

// A large Lambertian quad through the origin facing `normal`, seen head-on (it fills the view).
Scene plane_facing(const Vec3f& normal, float albedo) {
  Scene scene;
  scene.materials.push_back(test::diffuse({albedo, albedo, albedo}));
  const Vec3f a = std::abs(normal.y) > 0.5f ? Vec3f(1, 0, 0) : Vec3f(0, 1, 0);
  const Vec3f u = cross(normal, a) * 100.f, v = cross(normal, u);  // cross(u, v) ∥ normal
  test::add_mesh(scene, test::make_quad(u * -0.5f - v * 0.5f, u, v, 0));
  return scene;
}

test::TestRender render_plane(const Scene& scene, const Vec3f& normal, IntegratorKind integrator) {
  return test::render_rgb(scene, test::look_at(normal * 5.f, {0, 0, 0}, 20.f), 24, 24, 256, 1, 1, 0, integrator);
}

const IntegratorKind kIntegrators[] = {IntegratorKind::path, IntegratorKind::whitted};

}  // namespace

TEST_CASE("environment map: lat-long mapping with +Y up, the centre along +X, rotation about +Y") {
  const EnvironmentMapDesc white = make_map(8, 4, [](int, int) { return Rgb{1, 1, 1}; });
  const EnvironmentMap map(white);
  check_near(map.direction({0.5f, 0.5f}), {1, 0, 0});    // image centre
  check_near(map.direction({0.25f, 0.5f}), {0, 0, -1});  // where a glTF camera looks
  check_near(map.direction({0.75f, 0.5f}), {0, 0, 1});
  check_near(map.direction({0.f, 0.5f}), {-1, 0, 0});
  check_near(map.direction({0.3f, 0.f}), {0, 1, 0});   // top row
  check_near(map.direction({0.3f, 1.f}), {0, -1, 0});  // bottom row
  // Turned 90° about +Y (right-handed): the centre now looks along −Z.
  EnvironmentMapDesc white_turned = white;
  white_turned.rotation = radians(90.f);
  const EnvironmentMap turned(white_turned);
  check_near(turned.direction({0.5f, 0.5f}), {0, 0, -1});
  check_near(turned.direction({0.25f, 0.5f}), {-1, 0, 0});
  // uv and direction invert each other.
  Rng rng(2, 0);
  for (int i = 0; i < 100; ++i) {
    const Vec2f uv(rng.uniform(), 0.01f + 0.98f * rng.uniform());
    const Vec2f back = turned.uv(turned.direction(uv));
    CHECK(back.x == Approx(uv.x).margin(1e-5));
    CHECK(back.y == Approx(uv.y).margin(1e-5));
  }
  // Lookups: the texel column at the centre shows along +X, bilinear between texel centres.
  const EnvironmentMapDesc ramp_desc = make_map(8, 4, [](int x, int) { return Rgb{float(x), 0, 0}; });
  const EnvironmentMap ramp(ramp_desc);
  CHECK(ramp.radiance({1, 0, 0}).r == Approx(3.5f));                      // between columns 3 and 4
  CHECK(ramp.radiance(ramp.direction({4.5f / 8, 0.5f})).r == Approx(4));  // column 4's centre
  CHECK(ramp.radiance(ramp.direction({0.f, 0.5f})).r == Approx(3.5f));    // wraps: between 7 and 0
}

TEST_CASE("environment map: the sampling pdf integrates to 1 and reports what sample() does") {
  Rng rng(4, 0);
  std::vector<float> values(32 * 16);
  for (float& v : values) v = rng.uniform() < 0.2f ? 0.f : rng.uniform() * rng.uniform() * 20;
  const EnvironmentMapDesc desc = make_map(
      32, 16,
      [&](int x, int y) {
        return Rgb{values[y * 32 + x], 1, 0.5f};
      },
      radians(40.f), 3.f);
  const EnvironmentMap map(desc);
  // ∫ pdf dω = ∫∫ pdf sin θ dθ dφ (bounded even at the poles), midpoint rule.
  constexpr int kTheta = 400, kPhi = 800;
  double integral = 0;
  for (int i = 0; i < kTheta; ++i)
    for (int j = 0; j < kPhi; ++j) {
      const double theta = kPi * (i + 0.5) / kTheta, phi = 2 * kPi * (j + 0.5) / kPhi;
      const Vec3f w(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                    float(std::sin(theta) * std::sin(phi)));
      integral += map.pdf(w) * std::sin(theta) * (kPi / kTheta) * (2 * kPi / kPhi);
    }
  CHECK(integral == Approx(1).epsilon(1e-3));
  for (int i = 0; i < 1000; ++i) {
    const auto s = map.sample({rng.uniform(), rng.uniform()});
    if (!s) continue;
    INFO("sample " << i);
    CHECK(length(s->w) == Approx(1).epsilon(1e-5));
    CHECK(s->pdf == Approx(map.pdf(s->w)).epsilon(1e-3));
  }
}

TEST_CASE("environment map: sampled directions follow the pdf (chi-square)") {
  // A smooth sky with a bright lobe, dark at the poles (where a lat-long pdf has its 1/sin θ
  // cusp, which the test's cell integration in cos θ cannot resolve).
  const EnvironmentMapDesc sky = make_map(
      128, 64,
      [](int x, int y) {
        const float theta = kPi * (y + 0.5f) / 64, phi = 2 * kPi * (x + 0.5f) / 128;
        const float L = sqr(std::sin(theta)) * (2 + std::cos(phi) + 0.5f * std::sin(2 * phi) * std::cos(theta)) +
                        20 * std::exp(-20 * (sqr(theta - 1.f) + sqr(phi - 4.f)));
        return Rgb{L, 0.8f * L, 0.5f * L};
      },
      radians(25.f));
  const EnvironmentMap map(sky);
  // The map's +Y axis onto the χ² grid's z axis, by a cyclic (proper) permutation of the axes.
  const auto to_grid = [](const Vec3f& w) { return Vec3f(w.z, w.x, w.y); };
  const auto from_grid = [](const Vec3f& g) { return Vec3f(g.y, g.z, g.x); };
  const auto result = test::chi2_test(
      [&](float u1, float u2, float) -> std::optional<Vec3f> {
        const auto s = map.sample({u1, u2});
        return s ? std::optional<Vec3f>(to_grid(s->w)) : std::nullopt;
      },
      [&](const Vec3f& g) { return double(map.pdf(from_grid(g))); });
  INFO("chi2 " << result.statistic << ", dof " << result.degrees_of_freedom << ", p " << result.p_value);
  CHECK(result.passed);
}

TEST_CASE("furnace: a white sphere under a constant environment map renders 1, as under --env") {
  Scene scene;
  scene.materials.push_back(test::diffuse({1, 1, 1}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 3, 0));
  scene.environment_map = make_map(
      64, 32,
      [](int, int) {
        return Rgb{0.5f, 0.5f, 0.5f};
      },
      radians(10.f), 2.f);
  // The sphere fills the view but for the corners. Whitted samples only the light (no MIS with
  // the BSDF) and needs the many samples.
  const auto camera = test::look_at({0, 0, 5.f}, {0, 0, 0}, 20.f);
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    const auto img = test::render_rgb(scene, camera, 16, 16, 2048, 64, 1, 0, integrator);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 16, 16, 1.0, 0.01);
  }
}

TEST_CASE("environment map: a bright block of texels gives a plane the irradiance of its solid angle") {
  // Texels [36, 44) × [6, 12) of 64 × 32: φ over 2π · 8/64, θ from 6π/32 to 12π/32. On a plane
  // facing +Y, E = L ∫∫ cos θ sin θ dθ dφ = L Δφ (sin² θ₁ − sin² θ₀) / 2; the plane reflects ρE/π.
  const float L = 4, albedo = 0.5f;
  const double theta0 = kPi * 6 / 32, theta1 = kPi * 12 / 32, dphi = 2 * kPi * 8 / 64;
  const double E = L * dphi * (sqr(std::sin(theta1)) - sqr(std::sin(theta0))) / 2;
  Scene scene = plane_facing({0, 1, 0}, albedo);
  scene.environment_map = block_map(36, 6, 44, 12, L, radians(123.f));  // turning it changes nothing here
  for (const IntegratorKind integrator : kIntegrators) {
    INFO((integrator == IntegratorKind::path ? "path" : "whitted"));
    const auto img = render_plane(scene, {0, 1, 0}, integrator);
    CHECK(img.stats.invalid_samples == 0);
    test::check_mean(img, 0, 0, 24, 24, albedo * E / kPi, 0.01 * albedo * E / kPi);
  }
}

TEST_CASE("environment map: the image centre lights +X, turned 90 degrees it lights -Z, turned 180 none of +X") {
  // Texels [28, 36) × [12, 20): φ = 2πu from 157.5° to 202.5° around the centre, θ from 67.5° to
  // 112.5° around the horizon. On a plane facing +X, where ω · x = −sin θ cos φ:
  // E = L ∫ sin² θ dθ · ∫ −cos φ dφ.
  const float L = 2, albedo = 0.8f;
  const double theta0 = kPi * 12 / 32, theta1 = kPi * 20 / 32, phi0 = 2 * kPi * 28 / 64, phi1 = 2 * kPi * 36 / 64;
  const double sin2_integral = (theta1 - theta0) / 2 - (std::sin(2 * theta1) - std::sin(2 * theta0)) / 4;
  const double E = L * sin2_integral * (std::sin(phi0) - std::sin(phi1));
  const double expected = albedo * E / kPi;
  const struct {
    float rotation_degrees;
    Vec3f normal;
    double radiance;
  } cases[] = {{0, {1, 0, 0}, expected}, {90, {0, 0, -1}, expected}, {180, {1, 0, 0}, 0.0}};
  for (const auto& c : cases) {
    Scene scene = plane_facing(c.normal, albedo);
    scene.environment_map = block_map(28, 12, 36, 20, L, radians(c.rotation_degrees));
    for (const IntegratorKind integrator : kIntegrators) {
      INFO("rotation " << c.rotation_degrees << ", " << (integrator == IntegratorKind::path ? "path" : "whitted"));
      const auto img = render_plane(scene, c.normal, integrator);
      test::check_mean(img, 0, 0, 24, 24, c.radiance, c.radiance > 0 ? 0.01 * c.radiance : 1e-9);
    }
  }
}

TEST_CASE("environment maps load from .exr and .hdr alike, and bad files fail naming the file") {
  const auto dir = test::temp_dir("env_files");
  const int w = 6, h = 3;
  std::vector<float> rgb(w * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.1f + 0.37f * float(i % 7) * float(i % 5);
  const auto exr = dir / "sky.exr", hdr = dir / "sky.hdr";
  REQUIRE(stbi_write_hdr(hdr.c_str(), w, h, 3, rgb.data()));
  std::vector<float> with_negative = rgb;
  with_negative[4] = -0.5f;  // outside Rec.709 (RGBE cannot hold it): clamped to 0
  write_exr(exr, {w, h, with_negative, ColorPipeline::standard().chromaticities(ColorPipeline::kDefaultOutput), {}},
            false);
  const EnvironmentMapDesc from_exr = load_environment_map(exr, 30, 2);
  const EnvironmentMapDesc from_hdr = load_environment_map(hdr, 0, 1);
  CHECK(from_exr.rotation == Approx(radians(30.f)));
  CHECK(from_exr.scale == 2);
  REQUIRE(from_exr.image.rgb.size() == rgb.size());
  REQUIRE(from_hdr.image.rgb.size() == rgb.size());
  CHECK(from_exr.image.width == w);
  CHECK(from_hdr.image.height == h);
  for (size_t i = 0; i < rgb.size(); ++i) {
    INFO("value " << i);
    CHECK(from_exr.image.rgb[i] == (i == 4 ? 0.f : rgb[i]));
    // RGBE shares one exponent per pixel, with 8 bits of mantissa for each channel.
    const float pixel_max = std::max({rgb[i / 3 * 3], rgb[i / 3 * 3 + 1], rgb[i / 3 * 3 + 2]});
    CHECK(from_hdr.image.rgb[i] == Approx(rgb[i]).margin(pixel_max / 128));
  }

  const auto bad = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir / name) << content;
    return dir / name;
  };
  CHECK_THROWS_WITH(load_environment_map(dir / "absent.hdr", 0, 1),
                    Catch::Contains("absent.hdr") && Catch::Contains("no such file"));
  CHECK_THROWS_WITH(load_environment_map(bad("junk.hdr", "not an image"), 0, 1),
                    Catch::Contains("junk.hdr") && Catch::Contains("Radiance HDR"));
  CHECK_THROWS_WITH(load_environment_map(bad("junk.exr", "not an image"), 0, 1),
                    Catch::Contains("junk.exr") && Catch::Contains("OpenEXR"));
  CHECK_THROWS_WITH(load_environment_map(bad("sky.png", "x"), 0, 1),
                    Catch::Contains("sky.png") && Catch::Contains(".exr or .hdr"));
  std::vector<float> nan = rgb;
  nan[7] = std::nanf("");
  write_exr(dir / "nan.exr", {w, h, nan, ColorPipeline::standard().chromaticities(ColorPipeline::kDefaultOutput), {}},
            false);
  CHECK_THROWS_WITH(load_environment_map(dir / "nan.exr", 0, 1),
                    Catch::Contains("nan.exr") && Catch::Contains("not finite"));
  CHECK_THROWS_WITH(load_environment_map(exr, 0, -1), Catch::Contains("scale"));
}

TEST_CASE("images with spot, directional and image-environment lights are identical whatever the thread count") {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.7f, 0.4f, 0.2f}));
  test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1.f, 2, 0));
  test::add_mesh(scene, test::make_quad({-3, -1, 3}, {6, 0, 0}, {0, 0, -6}, 0));
  scene.spot_lights.push_back(
      {"spot", {1, 3, 1}, normalize(Vec3f(-1, -3, -1)), 0.2f, 0.5f, RgbIlluminantSpectrum(Rgb{30, 30, 30})});
  scene.directional_lights.push_back({"sun", normalize(Vec3f(1, -1, -1)), RgbIlluminantSpectrum(Rgb{2, 2, 1.5f})});
  scene.environment_map = make_map(
      16, 8,
      [](int x, int y) {
        return Rgb{0.1f * x, 0.05f * y, 0.3f};
      },
      1.f);
  const auto camera = test::look_at({0, 1, 4}, {0, 0, 0}, 40.f);
  for (const IntegratorKind integrator : kIntegrators) {
    const auto one = test::render_rgb(scene, camera, 40, 30, 4, 16, 7, 1, integrator);
    const auto two = test::render_rgb(scene, camera, 40, 30, 4, 16, 7, 2, integrator);
    CHECK(one.rgb == two.rgb);
    CHECK(one.stats.invalid_samples == 0);
  }
}
