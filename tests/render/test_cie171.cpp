// The analytical test cases of CIE 171:2006 ("Test cases to assess the accuracy of lighting
// computer programs") that Prism's meters (core/render/meter.h) can be held to, each answer
// computed here from its formula: a point source over a plane, a rectangular diffuse source over
// a parallel plane, the directional transmittance of a clear glass pane, and the diffuse
// inter-reflection inside a closed Lambertian enclosure.
// docs/validation/cie171.md reports the accuracy reached and what it costs.

#include <catch2/catch.hpp>
#include <cmath>

#include "core/render/meter.h"
#include "materials/fresnel.h"
#include "tests/support/sanitizers.h"
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

namespace {

// A clear pane's transmittance at incidence cos θ: each face reflects R_s and R_p (Fresnel), and the
// light bouncing between the faces sums to (1 − R)² / (1 − R²) = (1 − R) / (1 + R) for each
// polarisation; unpolarised light transmits their mean. `polarised` false: the sum over the mean R
// instead, the common shortcut the test must tell apart.
double pane_transmittance(double cos_theta, double eta, bool polarised = true) {
  const double c = cos_theta, g = std::sqrt(eta * eta - 1 + c * c);
  const double Rs = sqr((c - g) / (c + g)), Rp = sqr((eta * eta * c - g) / (eta * eta * c + g));
  const auto sheet = [](double R) { return (1 - R) / (1 + R); };
  return polarised ? (sheet(Rs) + sheet(Rp)) / 2 : sheet((Rs + Rp) / 2);
}

}  // namespace

TEST_CASE("CIE 171: a clear glass pane transmits (1 - R) / (1 + R) for each polarisation, at every incidence") {
  // A meter under a thin clear pane (index 1.5, smooth, both faces and the light between them, no
  // absorption) faces a rectangular diffuse source 10 m away at incidence θ on the pane: 8° from its
  // centre to its edges in the plane of incidence, 45° across it (the incidence varies little that
  // way). E = L ∫ T(θ_ω) cos(n, ω) dω over the source, integrated here at 300 × 300 points. Within
  // 0.5% of E_1 (the same without the pane) absolute, that is of T (twice that under the
  // sanitizers, sanitizers.h).
  constexpr double kEta = 1.5, kL = 100, kDistance = 10;
  for (const float incidence : {0.f, 30.f, 45.f, 60.f, 70.f}) {
    INFO("incidence " << incidence << " degrees");
    const double theta = radians(incidence), a = kDistance * std::tan(radians(8.f)),
                 b = kDistance * std::tan(radians(45.f));
    const Vec3d d(std::sin(theta), 0, std::cos(theta)), e1(std::cos(theta), 0, -std::sin(theta)), e2(0, 1, 0);
    Scene scene;
    scene.materials.push_back(
        Material{.name = "pane", .kind = PbrMaterial::glass(Dielectric(ConstantIor{float(kEta)}, {}, true))});
    Material source = lambertian(0, "source");
    source.emission = ConstantSpectrum{float(kL)};
    scene.materials.push_back(source);
    test::add_mesh(scene, test::make_quad({-200, -200, 0.01f}, {0, 400, 0}, {400, 0, 0}, 0));  // front −z
    const Vec3d corner = d * kDistance - e1 * a - e2 * b;
    test::add_mesh(scene, test::make_quad(Vec3f(corner), Vec3f(e2 * (2 * b)), Vec3f(e1 * (2 * a)), 1));  // front −d
    const World world(scene);

    // E with the pane (T), with the unpolarised shortcut, and without the pane (T = 1).
    double E = 0, E_unpolarised = 0, E_1 = 0;
    constexpr int kPoints = 300;
    for (int i = 0; i < kPoints; ++i)
      for (int j = 0; j < kPoints; ++j) {
        const Vec3d q = corner + e1 * (2 * a * (i + 0.5) / kPoints) + e2 * (2 * b * (j + 0.5) / kPoints);
        const double r = length(q), cos_source = dot(d, q) / r;  // the meter faces d, the source −d
        const double dw_cos = (2 * a / kPoints) * (2 * b / kPoints) * cos_source / (r * r) * cos_source;
        E += kL * pane_transmittance(q.z / r, kEta) * dw_cos;
        E_unpolarised += kL * pane_transmittance(q.z / r, kEta, false) * dw_cos;
        E_1 += kL * dw_cos;
      }
    // Sampled until the standard error is below a quarter of the tolerance (with 5% to spare).
    const double tolerance = 0.005 * test::kErrorScale, rel_error = 0.95 * tolerance * E_1 / 4 / E;
    const std::vector<MeterReading> r = measure(world, {{{0, 0, 0}, Vec3f(d)}}, meter_options(rel_error, 1 << 24));
    INFO("E " << r[0].illuminance << " ± " << r[0].std_error << " lx after " << r[0].samples << " samples, expected "
              << E << " lx (T " << E / E_1 << "; without polarisation " << E_unpolarised / E_1 << ")");
    REQUIRE(r[0].std_error <= tolerance * E_1 / 4);
    CHECK(std::abs(r[0].illuminance - E) <= tolerance * E_1);
    if (incidence >= 60)  // where the shortcut is off by more than the tolerance, the reading is too
      CHECK(std::abs(r[0].illuminance - E_unpolarised) > tolerance * E_1);
  }
}

TEST_CASE("CIE 171: inside a closed Lambertian sphere of reflectance rho, E = Phi / (S (1 - rho))") {
  // A point source of 100 cd (Φ = 4π · 100 lm) at the centre of a closed icosphere of radius 1. For
  // any closed enclosure of diffuse walls the energy balance Φ = (1 − ρ) ∫ E dA makes the
  // area-weighted mean illuminance Φ / (S (1 − ρ)); for a sphere every point has it. Meters on
  // every facet at the points of the 3-point rule exact for quadratics (barycentric (2/3, 1/6, 1/6)
  // and its permutations), facing in: the facets' mean illuminance, to well within the tolerance.
  for (const float rho : {0.f, 0.2f, 0.5f, 0.8f, 0.9f, 0.95f}) {
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
    const std::vector<MeterReading> r = measure(world, points, meter_options(0, test::sanitized_samples(256), 1000));
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

TEST_CASE(
    "CIE 171: inside a closed Lambertian cube the mean illuminance is Phi / (S (1 - rho)) too, not every point's") {
  // The energy balance holds for any closed diffuse enclosure; a cube is not uniformly lit (its
  // corners see the source at a slant and from farther), which the report quantifies.
  const float rho = 0.8f;
  Scene scene;
  scene.materials.push_back(lambertian(rho, "wall"));
  // Six faces of a cube of side 2 about the origin, each facing in.
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.f, 1.f}) {
      Vec3f u(0, 0, 0), v(0, 0, 0), origin(-1, -1, -1);
      u[(axis + 1) % 3] = 2, v[(axis + 2) % 3] = 2;
      origin[axis] = side;
      test::add_mesh(scene, side < 0 ? test::make_quad(origin, u, v, 0) : test::make_quad(origin, v, u, 0));
    }
  scene.point_lights.push_back({"source", {0, 0, 0}, ConstantSpectrum{100.f}});
  const World world(scene);
  // A 16 × 16 grid of cell centres on each face (the midpoint rule), facing in.
  constexpr int kCells = 16;
  std::vector<MeterPoint> points;
  for (int axis = 0; axis < 3; ++axis)
    for (const float side : {-1.f, 1.f})
      for (int i = 0; i < kCells; ++i)
        for (int j = 0; j < kCells; ++j) {
          Vec3f p(0, 0, 0), n(0, 0, 0);
          p[axis] = side, n[axis] = -side;
          p[(axis + 1) % 3] = -1 + 2 * (float(i) + 0.5f) / kCells;
          p[(axis + 2) % 3] = -1 + 2 * (float(j) + 0.5f) / kCells;
          points.push_back({p, n});
        }
  points.push_back({{0, 0, -1}, {0, 0, 1}});              // a face's centre
  points.push_back({{-0.999f, -0.999f, -1}, {0, 0, 1}});  // beside a corner
  const std::vector<MeterReading> r = measure(world, points, meter_options(0, 256, 1000));
  double mean = 0, variance = 0;
  const size_t grid = points.size() - 2;
  for (size_t i = 0; i < grid; ++i) {
    mean += r[i].illuminance / double(grid);
    variance += r[i].std_error * r[i].std_error / (double(grid) * grid);
  }
  const double expected = 4 * kPi * 100 / (24 * (1 - rho)), std_error = std::sqrt(variance);
  INFO("mean " << mean << " ± " << std_error << " lx, expected " << expected << " lx; a face's centre "
               << r[grid].illuminance << " lx, beside a corner " << r[grid + 1].illuminance << " lx");
  REQUIRE(std_error <= 0.01 * expected / 4);
  CHECK(std::abs(mean - expected) <= 0.01 * expected);
  // Not uniform: the centre of a face is lit well above the mean, a corner well below.
  CHECK(r[grid].illuminance > 1.1 * expected);
  CHECK(r[grid + 1].illuminance < 0.8 * expected);
}
