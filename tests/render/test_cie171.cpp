// The analytical test cases of CIE 171:2006 ("Test cases to assess the accuracy of lighting
// computer programs") that Prism's meters (core/render/meter.h) can be held to, each answer
// computed here from its formula: a point source over a plane, a rectangular diffuse source over
// a parallel plane, and the diffuse inter-reflection inside a closed Lambertian enclosure.
// docs/validation/cie171.md reports the accuracy reached and what it costs.

#include <catch2/catch.hpp>
#include <cmath>

#include "core/render/meter.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

Material lambertian(float albedo, const std::string& name) {
  return Material{.name = name, .kind = DiffuseMaterial{ConstantSpectrum{albedo}}};
}

MeterOptions meter_options(double rel_error, int max_spp, int max_depth = 64) {
  MeterOptions o;
  o.rel_error = rel_error;
  o.spp = max_spp;
  o.path.max_depth = max_depth;
  o.progress = false;
  return o;
}

// Each reading within `tolerance` (relative) of its expected value, after requiring its standard
// error to be below a quarter of that, so that the check means something.
void check_readings(const std::vector<MeterReading>& readings, const std::vector<double>& expected, double tolerance) {
  for (size_t i = 0; i < readings.size(); ++i) {
    INFO("meter " << i << ": " << readings[i].illuminance << " ± " << readings[i].std_error << " lx after "
                  << readings[i].samples << " samples, expected " << expected[i] << " lx");
    REQUIRE(readings[i].std_error <= tolerance * expected[i] / 4);
    CHECK(std::abs(readings[i].illuminance - expected[i]) <= tolerance * expected[i]);
  }
}

// Howell's configuration factor from a plane element to a parallel rectangle of sides a, b at
// distance h, the element below one of its corners (catalogue case B-3):
//   F = 1/(2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))],  X = a/h, Y = b/h.
double corner_factor(double a, double b, double h) {
  const double x = a / h, y = b / h, sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * kPi);
}

// The factor from a point (px, pz) at distance h below the rectangle [x0, x1] × [z0, z1], by
// adding and subtracting the corner rectangles at the point (signed sides).
double rectangle_factor(double x0, double x1, double z0, double z1, double px, double pz, double h) {
  const auto g = [&](double u, double v) {
    return (u < 0 ? -1 : 1) * (v < 0 ? -1 : 1) * corner_factor(std::abs(u), std::abs(v), h);
  };
  return g(x1 - px, z1 - pz) - g(x0 - px, z1 - pz) - g(x1 - px, z0 - pz) + g(x0 - px, z0 - pz);
}

}  // namespace

TEST_CASE("CIE 171: an isotropic point source over a plane gives E = I cos(theta) / d^2, on and off axis") {
  // 100 cd, 2 m above a black floor (nothing reflected): meters on the floor facing up, and one on
  // a wall facing the source sideways.
  Scene scene;
  scene.materials.push_back(lambertian(0, "floor"));
  test::add_mesh(scene, test::make_quad({-10, 0, 10}, {20, 0, 0}, {0, 0, -20}, 0));
  const float intensity = 100, h = 2;
  scene.point_lights.push_back({"source", {0, h, 0}, ConstantSpectrum{intensity}});
  const World world(scene);
  std::vector<MeterPoint> points;
  std::vector<double> expected;
  for (const float x : {0.f, 0.5f, 1.f, 2.f, 4.f, 8.f}) {
    points.push_back({{x, 0, 0}, {0, 1, 0}});
    const double d2 = double(h) * h + double(x) * x;
    expected.push_back(intensity * h / (d2 * std::sqrt(d2)));  // cos θ = h / d
  }
  points.push_back({{3, h, 0}, {-1, 0, 0}});  // a wall 3 m aside, at the source's height
  expected.push_back(intensity / 9.0);
  check_readings(measure(world, points, meter_options(0.002, 1 << 14)), expected, 0.01);
}

TEST_CASE("CIE 171: a rectangular diffuse source over a parallel plane gives E = L pi F (Howell)") {
  // A 2 m × 1 m panel of 1000 cd/m² facing down, 1.5 m above meters facing up: below its centre,
  // below a corner, and beside it.
  Scene scene;
  Material panel = lambertian(0, "panel");
  panel.emission = ConstantSpectrum{1000.f};
  scene.materials.push_back(panel);
  const double x0 = -1, x1 = 1, z0 = -0.5, z1 = 0.5, h = 1.5;
  test::add_mesh(scene, test::make_quad({float(x0), float(h), float(z0)}, {float(x1 - x0), 0, 0},
                                        {0, 0, float(z1 - z0)}, 0));  // front side −y
  const World world(scene);
  std::vector<MeterPoint> points;
  std::vector<double> expected;
  for (const auto& [px, pz] : {std::pair{0.0, 0.0}, {0.6, 0.2}, {1.0, 0.5}, {2.0, 0.0}, {-1.5, 1.5}}) {
    points.push_back({{float(px), 0, float(pz)}, {0, 1, 0}});
    expected.push_back(1000 * kPi * rectangle_factor(x0, x1, z0, z1, px, pz, h));
  }
  check_readings(measure(world, points, meter_options(0.002, 1 << 18)), expected, 0.01);
}

TEST_CASE("CIE 171: inside a closed Lambertian sphere of reflectance rho, E = Phi / (S (1 - rho))") {
  // A point source of 100 cd (Φ = 4π · 100 lm) at the centre of a closed icosphere of radius 1. For
  // any closed enclosure of diffuse walls the energy balance Φ = (1 − ρ) ∫ E dA makes the
  // area-weighted mean illuminance Φ / (S (1 − ρ)); for a sphere every point has it. Meters on
  // every facet at the points of the 3-point rule exact for quadratics (barycentric (2/3, 1/6, 1/6)
  // and its permutations), facing in: the facets' mean illuminance, to well within the tolerance.
  for (const float rho : {0.f, 0.2f, 0.5f, 0.8f, 0.9f}) {
    INFO("reflectance " << rho);
    Scene scene;
    scene.materials.push_back(lambertian(rho, "wall"));
    test::add_mesh(scene, test::make_icosphere({0, 0, 0}, 1, 2, 0));
    scene.point_lights.push_back({"source", {0, 0, 0}, ConstantSpectrum{100.f}});
    const World world(scene);
    const Mesh& sphere = scene.meshes[0];
    std::vector<MeterPoint> points;
    std::vector<double> areas;
    double area = 0;
    for (size_t t = 0; t < sphere.indices.size(); t += 3) {
      const Vec3f a = sphere.positions[sphere.indices[t]], b = sphere.positions[sphere.indices[t + 1]],
                  c = sphere.positions[sphere.indices[t + 2]];
      const Vec3f n = cross(b - a, c - a);
      for (const Vec3f& corner : {a, b, c}) {
        points.push_back({corner * (2.f / 3) + (a + b + c - corner) / 6.f, -normalize(n)});
        areas.push_back(0.5 * double(length(n)) / 3);
      }
      area += 0.5 * double(length(n));
    }
    const double expected = 4 * kPi * 100 / (area * (1 - rho));
    const std::vector<MeterReading> r = measure(world, points, meter_options(0, 256, 1000));
    double mean = 0, variance = 0;
    for (size_t i = 0; i < r.size(); ++i) {
      mean += areas[i] * r[i].illuminance / area;
      variance += (areas[i] / area) * (areas[i] / area) * r[i].std_error * r[i].std_error;
    }
    const double std_error = std::sqrt(variance);
    INFO("area-weighted mean " << mean << " ± " << std_error << " lx, expected " << expected << " lx");
    REQUIRE(std_error <= 0.01 * expected / 4);
    CHECK(std::abs(mean - expected) <= 0.01 * expected);
  }
}
