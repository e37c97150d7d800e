// The light tree (light_tree.h) against what it claims, on a scene of every light type: the
// probability it reports for a light at a point is the frequency with which it picks that light
// (χ² over the lights), it is above zero for every light that can light the point, and light
// sampling with it agrees with a brute-force integral of the direct light. Then renders of a
// many-light scene: tree and power sampling, and BDPT and VCM with the tree, agree within noise;
// a render is the same whatever the thread count.

#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "core/base/rng.h"
#include "core/render/light_tree.h"
#include "core/render/world.h"
#include "tests/support/chi2.h"
#include "tests/support/sanitizers.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Vec3f random_vector(Rng& rng, float scale) {
  return Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * scale;
}

// 120 small emissive quads in a 10 m cube, facing every way, of three materials (one-sided bright,
// one-sided dim, two-sided), two point lights, two spot lights, a directional light and a sky.
Scene every_light_scene() {
  Scene scene;
  const Rgb colours[3] = {{4.f, 3.f, 2.f}, {0.2f, 0.3f, 0.5f}, {1.f, 1.f, 1.f}};
  for (int m = 0; m < 3; ++m) {
    Material e = test::diffuse({0.5f, 0.5f, 0.5f}, "lamp");
    e.emission = RgbIlluminantSpectrum(colours[m]);
    e.double_sided = m == 2;
    scene.materials.push_back(e);
  }
  Rng rng(7, 0);
  for (int i = 0; i < 120; ++i) {
    const float size = 0.05f + 0.5f * rng.uniform();
    test::add_mesh(scene, test::make_quad(random_vector(rng, 10.f), random_vector(rng, size * 2),
                                          random_vector(rng, size * 2), uint32_t(i % 3)));
  }
  scene.point_lights.push_back({"p0", {2.f, 3.f, -1.f}, RgbIlluminantSpectrum(Rgb{5.f, 5.f, 5.f})});
  scene.point_lights.push_back({"p1", {-4.f, -2.f, 4.f}, RgbIlluminantSpectrum(Rgb{1.f, 2.f, 1.f})});
  scene.spot_lights.push_back(
      {"s0", {0.f, 6.f, 0.f}, {0.f, -1.f, 0.f}, 0.2f, 0.5f, RgbIlluminantSpectrum(Rgb{20.f, 20.f, 20.f})});
  scene.spot_lights.push_back({"s1",
                               {3.f, -3.f, 3.f},
                               normalize(Vec3f(-1.f, 1.f, -1.f)),
                               0.3f,
                               0.3f,
                               RgbIlluminantSpectrum(Rgb{9.f, 9.f, 9.f})});
  scene.directional_lights.push_back(
      {"sun", normalize(Vec3f(0.3f, -1.f, 0.2f)), RgbIlluminantSpectrum(Rgb{2.f, 2.f, 2.f})});
  scene.environment = RgbIlluminantSpectrum(Rgb{0.05f, 0.05f, 0.05f});
  return scene;
}

// Shading points under, inside, beside, far from and above the lights; with a one-sided
// receiver's axis (reflect_axis: the tree bounds light from below it at zero), or a surface that
// transmits (either side).
std::vector<LightSampleContext> shading_points() {
  const Vec3f up(0.f, 1.f, 0.f), zero(0.f, 0.f, 0.f);
  return {
      {{0.f, -6.f, 0.f}, {}, up, up},                                        // under the lights, facing them
      {{0.f, 7.f, 0.f}, {}, up, up},                                         // above, facing away: back-facing
      {{0.5f, 0.2f, -0.3f}, {}, up, zero},                                   // among them, transmitting
      {{6.f, 0.f, 1.f}, {}, {-1.f, 0.f, 0.f}, {-1.f, 0.f, 0.f}},             // beside, facing them
      {{60.f, 30.f, -40.f}, {}, normalize(Vec3f(-1.f, -0.5f, 0.7f)), zero},  // far away
  };
}

// Whether light `i` can bring any light to the point of ctx: some point of it emits towards the
// point, from above the receiving side when there is one.
bool can_light(const World& world, uint32_t i, const LightSampleContext& ctx) {
  const bool one_sided = ctx.reflect_axis != Vec3f(0.f, 0.f, 0.f);
  const auto above = [&](const Vec3f& q) { return !one_sided || dot(q - ctx.p, ctx.reflect_axis) > 0; };
  const Light& light = world.lights()[i];
  if (const auto* a = std::get_if<AreaLight>(&light)) {
    for (int s = 0; s < 16; ++s)
      for (int t = 0; s + t < 16; ++t) {
        const Vec3f q = a->p0 * (1 - (s + t) / 15.f) + a->p1 * (s / 15.f) + a->p2 * (t / 15.f);
        if (a->emits_towards(ctx.p - q) && above(q)) return true;
      }
    return false;
  }
  if (const auto* p = std::get_if<PointLightSource>(&light)) return above(p->position);
  if (const auto* s = std::get_if<SpotLightSource>(&light))
    return above(s->point.position) && s->attenuation(dot(s->direction, normalize(ctx.p - s->point.position))) > 0;
  return true;  // directional and the sky: outside the tree, chosen by power everywhere
}

// The χ² p-value of `counts` of `samples` draws against probabilities `pmf` (cells of fewer than 5
// expected draws pooled; the draws that chose nothing are a cell of their own).
double chi2_p_value(const std::vector<double>& pmf, const std::vector<int>& counts, int samples) {
  double total_pmf = 0, stat = 0, pooled_expected = 0, pooled_count = 0;
  int cells = 0, chosen = 0;
  const auto add = [&](double expected, double count) {
    stat += (count - expected) * (count - expected) / expected;
    ++cells;
  };
  for (size_t i = 0; i < pmf.size(); ++i) {
    total_pmf += pmf[i], chosen += counts[i];
    const double expected = pmf[i] * samples;
    if (expected >= 5)
      add(expected, counts[i]);
    else
      pooled_expected += expected, pooled_count += counts[i];
  }
  pooled_expected += (1 - total_pmf) * samples, pooled_count += samples - chosen;
  if (pooled_expected >= 5)
    add(pooled_expected, pooled_count);
  else
    CHECK(pooled_count <= 5 + 5 * std::sqrt(5.0));
  return 1 - test::regularized_gamma_p((cells - 1) / 2.0, stat / 2);
}

}  // namespace

TEST_CASE("the light tree's pmf is how often it picks each light, and above zero wherever the light reaches") {
  const Scene scene = every_light_scene();
  const World world(scene, {}, LightSamplerKind::tree);
  const LightSampler& sampler = world.light_sampler();
  REQUIRE(sampler.tree() != nullptr);
  const uint32_t n = uint32_t(world.lights().size());
  const int samples = test::sanitized_samples(400000);
  // And points barely in front of some lamps' planes, beside them: lit at a grazing angle, at
  // the edge of what the cones bound.
  std::vector<LightSampleContext> points = shading_points();
  for (uint32_t i = 0; i < n; i += 12)
    if (const auto* a = std::get_if<AreaLight>(&world.lights()[i])) {
      const Vec3f centre = (a->p0 + a->p1 + a->p2) / 3.f;
      points.push_back({a->p0 + (a->p0 - centre) + a->n * (0.01f * length(a->p0 - centre)), {}, a->n, {}});
    }
  Rng rng(3, 0);
  for (const LightSampleContext& ctx : points) {
    INFO("point " << ctx.p.x << "," << ctx.p.y << "," << ctx.p.z);
    std::vector<double> pmf(n);
    std::vector<int> counts(n, 0);
    for (uint32_t i = 0; i < n; ++i) pmf[i] = sampler.pmf(ctx, i);
    for (int k = 0; k < samples; ++k)
      if (const auto s = sampler.sample(ctx, rng.uniform())) {
        REQUIRE(s->light < n);
        CHECK(s->pmf == Approx(pmf[s->light]).epsilon(1e-5));
        ++counts[s->light];
      }
    for (uint32_t i = 0; i < n; ++i) {
      INFO("light " << i);
      if (counts[i] > 0) CHECK(pmf[i] > 0);
      if (can_light(world, i, ctx)) CHECK(pmf[i] > 0);
    }
    CHECK(chi2_p_value(pmf, counts, samples) > 1e-4);
  }
}

TEST_CASE("direct light sampled through the light tree equals its brute-force integral") {
  // The irradiance at a receiver from every light, unoccluded: Σ over the lights of ∫ L cos⁺ dω, by
  // sampling each light alone many times, against one light chosen by the tree per sample.
  const Scene scene = every_light_scene();
  const World tree(scene, {}, LightSamplerKind::tree);
  const auto lambda = SampledWavelengths<1>::sample({0.37f, 0.5f});
  const int samples = test::sanitized_samples(200000);
  for (const LightSampleContext& ctx : shading_points()) {
    if (ctx.reflect_axis == Vec3f(0.f, 0.f, 0.f)) continue;  // a receiver has a side
    INFO("point " << ctx.p.x << "," << ctx.p.y << "," << ctx.p.z);
    const auto contribution = [&](const Light& light, Vec2f u) -> double {
      const auto s = sample_li(light, ctx, u, lambda);
      if (!s) return 0;
      return double(s->L[0]) * std::max(0.f, dot(s->wi, ctx.reflect_axis)) / s->pdf;
    };
    Rng rng(11, 0);
    // Brute force: every light, samples / 20 each (point, spot and directional lights exactly).
    double brute = 0, brute_var = 0;
    for (const Light& light : tree.lights()) {
      const int m = is_delta(light) ? 1 : samples / 20;
      double sum = 0, sum2 = 0;
      for (int k = 0; k < m; ++k) {
        const double c = contribution(light, {rng.uniform(), rng.uniform()});
        sum += c, sum2 += c * c;
      }
      brute += sum / m;
      if (m > 1) brute_var += std::max(0.0, sum2 / m - (sum / m) * (sum / m)) / (m - 1);
    }
    double sum = 0, sum2 = 0;
    for (int k = 0; k < samples; ++k) {
      const auto chosen = tree.light_sampler().sample(ctx, rng.uniform());
      const Vec2f u{rng.uniform(), rng.uniform()};
      const double c = chosen ? contribution(tree.lights()[chosen->light], u) / chosen->pmf : 0;
      sum += c, sum2 += c * c;
    }
    const double estimate = sum / samples;
    const double variance = std::max(0.0, sum2 / samples - estimate * estimate) / (samples - 1);
    REQUIRE(brute > 0);
    CHECK(std::abs(estimate - brute) <= 4 * std::sqrt(variance + brute_var) + 1e-6 * brute);
  }
}

TEST_CASE("a light tree is built only where it has a choice to make") {
  Scene one;
  one.point_lights.push_back({"p", {0.f, 1.f, 0.f}, RgbIlluminantSpectrum(Rgb{1.f, 1.f, 1.f})});
  one.environment = RgbIlluminantSpectrum(Rgb{1.f, 1.f, 1.f});
  CHECK(World(one, {}, LightSamplerKind::tree).light_sampler().tree() == nullptr);
  one.point_lights.push_back({"q", {0.f, 2.f, 0.f}, RgbIlluminantSpectrum(Rgb{1.f, 1.f, 1.f})});
  CHECK(World(one, {}, LightSamplerKind::tree).light_sampler().tree() != nullptr);
  CHECK(World(one, {}, LightSamplerKind::power).light_sampler().tree() == nullptr);
  CHECK(World(one, {}, LightSamplerKind::automatic).light_sampler().tree() == nullptr);  // two: power
  one.point_lights.push_back({"r", {0.f, 3.f, 0.f}, RgbIlluminantSpectrum(Rgb{1.f, 1.f, 1.f})});
  CHECK(World(one, {}, LightSamplerKind::automatic).light_sampler().tree() != nullptr);
}

namespace {

// A floor lit by a 16 × 16 grid of small lamps of three colours facing down, with two blocks
// between them and the floor casting shadows; seen from above at an angle.
Scene lamp_grid_scene() {
  Scene scene;
  scene.materials.push_back(test::diffuse({0.6f, 0.6f, 0.6f}, "floor"));
  const Rgb colours[3] = {{3.f, 1.f, 0.5f}, {0.5f, 3.f, 1.f}, {1.f, 0.5f, 3.f}};
  for (const Rgb& c : colours) {
    Material e = test::diffuse({0.5f, 0.5f, 0.5f}, "lamp");
    e.emission = RgbIlluminantSpectrum(c);
    scene.materials.push_back(e);
  }
  test::add_mesh(scene, test::make_quad({-10, 0, -10}, {0, 0, 20}, {20, 0, 0}, 0));  // front = +Y
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j)  // front = −Y
      test::add_mesh(scene, test::make_quad({-8.f + i, 2.f, -8.f + j}, {0.3f, 0, 0}, {0, 0, 0.3f}, 1 + (i + j) % 3));
  test::add_mesh(scene, test::make_icosphere({-2.f, 0.8f, 1.f}, 0.8f, 2, 0));
  test::add_mesh(scene, test::make_icosphere({3.f, 1.f, -2.f}, 0.6f, 2, 0));
  return scene;
}

CameraDesc lamp_grid_camera() { return test::look_at({0.f, 1.5f, -9.f}, {0.f, 0.f, 0.f}, 60.f); }

RenderOptions lamp_grid_options(IntegratorKind integrator, int spp, int threads = 0) {
  RenderOptions o;
  o.integrator = integrator;
  o.spp = spp;
  o.threads = threads;
  o.path.max_depth = 4;
  return o;
}

// The mean of a − b over the image, channel by channel, is zero within noise.
void check_same_mean(const test::TestRender& a, const test::TestRender& b) {
  for (int c = 0; c < 3; ++c) {
    const test::MeanDifference d = test::mean_difference(a, b, c);
    INFO("channel " << c << ": a − b = " << d.difference << " ± " << d.standard_error << " (a's mean " << a.mean(c)
                    << ")");
    CHECK(std::abs(d.difference) <= 4 * d.standard_error);
    CHECK(d.standard_error < 0.01 * test::kErrorScale * a.mean(c));
  }
}

}  // namespace

TEST_CASE("a many-light scene renders the same with the light tree and power sampling, in every integrator") {
  const Scene scene = lamp_grid_scene();
  const World tree(scene, {}, LightSamplerKind::tree), power(scene, {}, LightSamplerKind::power);
  const int spp = test::sanitized_samples(64);
  const auto path = test::render_rgb(tree, lamp_grid_camera(), 48, 32, lamp_grid_options(IntegratorKind::path, spp));
  CHECK(path.stats.invalid_samples == 0);
  SECTION("path tracing, power sampling") {
    const auto other =
        test::render_rgb(power, lamp_grid_camera(), 48, 32, lamp_grid_options(IntegratorKind::path, 4 * spp));
    check_same_mean(path, other);
  }
  SECTION("BDPT with the tree") {
    const auto other = test::render_rgb(tree, lamp_grid_camera(), 48, 32, lamp_grid_options(IntegratorKind::bdpt, spp));
    CHECK(other.stats.invalid_samples == 0);
    check_same_mean(path, other);
  }
  SECTION("VCM with the tree") {
    const auto other = test::render_rgb(tree, lamp_grid_camera(), 48, 32, lamp_grid_options(IntegratorKind::vcm, spp));
    CHECK(other.stats.invalid_samples == 0);
    check_same_mean(path, other);
  }
}

TEST_CASE("a render with the light tree is the same on one thread as on several") {
  const Scene scene = lamp_grid_scene();
  const World world(scene, {}, LightSamplerKind::tree);
  const auto one = test::render_rgb(world, lamp_grid_camera(), 24, 16, lamp_grid_options(IntegratorKind::path, 4, 1));
  const auto four = test::render_rgb(world, lamp_grid_camera(), 24, 16, lamp_grid_options(IntegratorKind::path, 4, 4));
  CHECK(one.rgb == four.rgb);
}

TEST_CASE("a light tree's choices sum to one, from a single light to thousands") {
  // Lamps facing down from a ceiling, as in a hall: every one of them lights a point on the floor.
  for (const size_t count : {size_t(1), size_t(2), size_t(9), size_t(64), size_t(10'000)}) {
    Rng rng(3, count);
    std::vector<std::optional<LightBounds>> bounds(count);
    std::vector<float> power(count);
    for (size_t i = 0; i < count; ++i) {
      const Vec3f c(100 * rng.uniform(), 10.f, 100 * rng.uniform());
      power[i] = 0.5f + rng.uniform();
      bounds[i] = LightBounds{{c - Vec3f(0.1f, 0.f, 0.1f), c + Vec3f(0.1f, 0.f, 0.1f)}, {0.f, -1.f, 0.f}, power[i]};
    }
    const LightTree tree(bounds, power);
    const ShadingPoint at{{50.f, 0.f, 50.f}, {0.f, 1.f, 0.f}, true};
    double sum = 0;
    for (uint32_t i = 0; i < count; ++i) {
      const float pmf = tree.pmf(at, i);
      CHECK(pmf > 0);
      sum += pmf;
    }
    INFO(count << " lights");
    CHECK(sum == Approx(1.0).epsilon(1e-4));
  }
}
