// Emission sampled by its texture (textured_emission.h): the sub-triangles tile the triangle, a
// sample's reported density is the density there, and the density integrates to one. Then a quad
// with one bright texel lights a floor with the analytic irradiance of that texel's patch, light
// sampling and BSDF sampling weighed by MIS together, with the low noise that sampling by the
// texture gives and sampling the quad uniformly could not; in the path tracer and in BDPT (whose
// light paths start from the texel too).

#include <catch2/catch.hpp>
#include <cmath>

#include "core/base/rng.h"
#include "core/render/textured_emission.h"
#include "core/render/world.h"
#include "tests/support/sanitizers.h"
#include "tests/support/test_scenes.h"

using namespace prism;

TEST_CASE("a textured triangle's sub-triangles tile it, and its density is that of its samples") {
  for (int k : {1, 2, 3, 7, 16}) {
    INFO("k = " << k);
    // Equal areas adding up to the triangle's (1/2 in barycentric coordinates), inside it.
    double area = 0;
    for (int i = 0; i < TexturedEmission::count(k); ++i) {
      const auto c = TexturedEmission::corners(k, i);
      const Vec2f e1 = c[1] - c[0], e2 = c[2] - c[0];
      const double a = 0.5 * std::abs(double(e1.x) * e2.y - double(e1.y) * e2.x);
      CHECK(a == Approx(0.5 / (k * k)).epsilon(1e-5));
      area += a;
      for (const Vec2f& p : c) CHECK((p.x >= 0 && p.y >= 0 && p.x + p.y <= 1 + 1e-6f));
    }
    CHECK(area == Approx(0.5).epsilon(1e-5));
    std::vector<float> weight(size_t(TexturedEmission::count(k)));
    Rng rng(uint64_t(k), 0);
    for (float& w : weight) w = rng.uniform() < 0.3f ? 0.f : rng.uniform();
    weight[0] = 1;
    const TexturedEmission t(k, weight);
    // Samples land where their density says, and never where the weight is zero.
    for (int n = 0; n < 2000; ++n) {
      const auto s = t.sample({rng.uniform(), rng.uniform()});
      CHECK(s.b.x + s.b.y + s.b.z == Approx(1).epsilon(1e-5));
      CHECK(s.density > 0);
      CHECK(t.density(s.b) == Approx(s.density).epsilon(1e-4));
    }
    // ∫ density dA / A = 1: its mean over uniform points.
    double sum = 0;
    const int points = 200000;
    for (int n = 0; n < points; ++n) {
      float b1 = rng.uniform(), b2 = rng.uniform();
      if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
      sum += t.density({1 - b1 - b2, b1, b2});
    }
    CHECK(sum / points == Approx(1).epsilon(0.02));
  }
}

namespace {

constexpr float kAlbedo = 0.5f, kRadiance = 20.f;
constexpr int kTexels = 8, kBrightX = 5, kBrightY = 2;

// A floor (y = 0) under a 2 m square lamp facing down at y = 1, whose 8 × 8 texture is black
// but for one white texel (nearest filtering: a sharp 0.25 m square of radiance kRadiance).
Scene texel_lamp_scene() {
  Scene scene;
  scene.materials.push_back(test::diffuse({kAlbedo, kAlbedo, kAlbedo}, "floor"));
  Material lamp = test::diffuse({0.f, 0.f, 0.f}, "lamp");
  lamp.emission_rgb = {kRadiance, kRadiance, kRadiance};
  lamp.emission = RgbIlluminantSpectrum(lamp.emission_rgb);
  Texture texture;
  std::vector<uint8_t> rgba(kTexels * kTexels * 4, 0);
  for (int c = 0; c < 4; ++c) rgba[size_t(kBrightY * kTexels + kBrightX) * 4 + size_t(c)] = 255;
  texture.image = std::make_shared<Image>(kTexels, kTexels, std::move(rgba));
  texture.nearest = true;
  lamp.emission_texture = texture;
  scene.materials.push_back(lamp);
  test::add_mesh(scene, test::make_quad({-20, 0, -20}, {0, 0, 40}, {40, 0, 0}, 0));  // front = +y
  Mesh quad = test::make_quad({-1, 1, -1}, {2, 0, 0}, {0, 0, 2}, 1);                 // front = −y
  quad.uv[0] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};                                     // u along x, v along z
  test::add_mesh(scene, std::move(quad));
  return scene;
}

// The irradiance at floor point (x, 0, z) from the bright texel's square, by the midpoint rule.
double texel_irradiance(double x, double z) {
  const double size = 2.0 / kTexels, x0 = -1 + kBrightX * size, z0 = -1 + kBrightY * size;
  constexpr int n = 48;
  double e = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double dx = x0 + (i + 0.5) * size / n - x, dz = z0 + (j + 0.5) * size / n - z;
      const double r2 = dx * dx + 1 + dz * dz;
      e += 1 / (r2 * r2);  // cos θ · cos θ' / r² with both cosines 1 / r
    }
  return kRadiance * e * (size / n) * (size / n);
}

}  // namespace

TEST_CASE("a lamp's one bright texel lights the floor as its patch does, sampled by the texture") {
  const Scene scene = texel_lamp_scene();
  const World world(scene);
  // The square [−1.5, 1.5]² of the floor, seen straight down from below the lamp.
  constexpr int n = 24;
  constexpr float half = 1.5f;
  CameraDesc c;
  c.projection = CameraDesc::Projection::orthographic;
  c.xmag = c.ymag = half;
  const Vec3f eye(0.f, 0.5f, 0.f), right(1, 0, 0), up(0, 0, -1), back(0, 1, 0);
  for (int r = 0; r < 3; ++r) {
    c.to_world.m[r][0] = right[r];
    c.to_world.m[r][1] = up[r];
    c.to_world.m[r][2] = back[r];
    c.to_world.m[r][3] = eye[r];
  }
  const IntegratorKind integrator = GENERATE(IntegratorKind::path, IntegratorKind::bdpt);
  INFO("integrator " << int(integrator));
  RenderOptions options;
  options.spp = test::sanitized_samples(256);
  options.path.max_depth = 1;
  options.integrator = integrator;
  const test::TestRender image = test::render_rgb(world, c, n, n, options);
  CHECK(image.stats.invalid_samples == 0);
  // Pixel (i, j) covers x ∈ −half + [i, i + 1] · 2 half / n, z ∈ −half + [j, j + 1] · 2 half / n (up is −z).
  double rendered = 0, expected = 0, variance = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      double e = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          e += texel_irradiance(-half + (i + (a + 0.5) / 4) * 2 * half / n, -half + (j + (b + 0.5) / 4) * 2 * half / n);
      e *= kAlbedo / kPi / 16;
      const double r = image.rgb[size_t(j * n + i) * 3 + 1];
      rendered += r, expected += e;
      variance += (r - e) * (r - e);
    }
  INFO("rendered " << rendered << ", expected " << expected);
  CHECK(rendered == Approx(expected).epsilon(0.01 * test::kErrorScale));
  // Per pixel within a few per cent (RMS): sampling the quad uniformly, its bright texel one
  // sample in 64, leaves about half the mean.
  CHECK(std::sqrt(variance / (n * n)) < 0.1 * test::kErrorScale * expected / (n * n));
}
