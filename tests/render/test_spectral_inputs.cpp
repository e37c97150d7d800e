// Spectra given in a glTF file (README, "Spectral inputs") render as the colorimetry says: a
// patch of reflectance ρ(λ) lit by a light of spectrum S(λ) shows the XYZ of ∫ρ S {x̄, ȳ, z̄}
// normalised by ∫S ȳ, an emitter of spectrum S shows S's colour at the luminance its glTF factors
// give, and D65 and E round trip through every path.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "core/scene/gltf_loader.h"
#include "spectral/cie.h"
#include "spectral/named_spectra.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

// The mean XYZ of a render of the quad scene, with the standard error of each channel's mean
// (from the spread of the pixels, which are independent estimates).
struct MeanXyz {
  double value[3], error[3];
};

MeanXyz render_xyz(const Scene& scene, int spp = 64) {
  RenderOptions options;
  options.spp = spp;
  options.progress = false;
  const World world(scene);
  const Camera camera(scene.cameras.at(0), 16, 16);
  const std::vector<float> xyz = render(world, camera, options).state.film.xyz_image();
  MeanXyz m{};
  const double n = double(xyz.size() / 3);
  for (int c = 0; c < 3; ++c) {
    double sum = 0, sq = 0;
    for (size_t p = 0; p < xyz.size() / 3; ++p) sum += xyz[p * 3 + c], sq += double(xyz[p * 3 + c]) * xyz[p * 3 + c];
    m.value[c] = sum / n;
    m.error[c] = std::sqrt(std::max(0.0, sq / n - m.value[c] * m.value[c]) / (n - 1));
  }
  return m;
}

// ∫ f(λ) {x̄, ȳ, z̄}(λ) dλ / ∫ȳ over 360–830 nm, with the tables linear between their 1-nm rows (as
// the film reads them), by a fine midpoint sum.
template <typename F>
std::array<double, 3> integrate_xyz(const F& f) {
  const CieTables& t = cie();
  std::array<double, 3> sum{0, 0, 0};
  double y_integral = 0;
  constexpr double step = 0.05;
  for (double l = kLambdaMin + step / 2; l < kLambdaMax; l += step) {
    const double v = f(l);
    sum[0] += v * t.x(float(l)) * step, sum[1] += v * t.y(float(l)) * step, sum[2] += v * t.z(float(l)) * step;
    y_integral += t.y(float(l)) * step;
  }
  for (double& s : sum) s /= y_integral;
  return sum;
}

void check_xyz(const MeanXyz& m, const std::array<double, 3>& expected, double relative) {
  for (int c = 0; c < 3; ++c) {
    INFO("channel " << c << ": rendered " << m.value[c] << " ± " << m.error[c] << ", expected " << expected[c]);
    REQUIRE(m.error[c] <= relative * expected[c] / 4);  // precise enough for the check to mean something
    CHECK(std::abs(m.value[c] - expected[c]) <= relative * expected[c]);
  }
}

void write(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

}  // namespace

TEST_CASE("a patch of reflectance rho under a light of spectrum S shows the XYZ of the integral of rho S") {
  const auto dir = test::temp_dir("spectral_patch");
  // ρ: a table with 0 outside 380–780 nm (linear between its points), as a glTF table and a file.
  const std::vector<float> rho_l = {380, 480, 580, 680, 780}, rho_v = {0.1f, 0.7f, 0.3f, 0.9f, 0.5f};
  const TabulatedSpectrum rho(rho_l, rho_v, TabulatedSpectrum::Outside::zero);
  write(dir / "rho.csv", "wavelength_nm,reflectance\n380,0.1\n480,0.7\n580,0.3\n680,0.9\n780,0.5\n");
  const std::string rho_table = R"({"wavelengths": [380, 480, 580, 680, 780], "values": [0.1, 0.7, 0.3, 0.9, 0.5]})";
  // S: a named illuminant, a blackbody, a table, and a file (a narrow green line on a weak floor).
  write(dir / "lamp.csv", "# a test lamp\n400,0.2\n520,0.2\n540,3\n560,0.2\n700,0.2\n");
  const TabulatedSpectrum lamp({400, 520, 540, 560, 700}, {0.2f, 0.2f, 3, 0.2f, 0.2f},
                               TabulatedSpectrum::Outside::zero);
  const TabulatedSpectrum table({450, 600, 650}, {1, 2, 0.5f}, TabulatedSpectrum::Outside::zero);
  struct Case {
    const char* name;
    std::string light_spectrum, reflectance;
    Spectrum s;
  };
  const Case cases[] = {
      {"named F11", R"("F11")", rho_table, *named_illuminant("F11")},
      {"blackbody 3000 K", R"({"blackbody": 3000})", rho_table, BlackbodySpectrum(3000)},
      {"table", R"({"wavelengths": [450, 600, 650], "values": [1, 2, 0.5]})", rho_table, table},
      {"file", R"({"file": "lamp.csv"})", R"({"file": "rho.csv"})", lamp},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    // A directional light of 2 lux straight down onto a Lambertian patch (no specular layer): the
    // patch's radiance is ρ(λ) · 2/π · S(λ) / Y(S), S scaled to the light's luminance.
    const auto path = test::write_quad_scene(
        dir, "patch",
        R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0},
            "extensions": {"KHR_materials_specular": {"specularFactor": 0}},
            "extras": {"prism": {"reflectance": )" +
            c.reflectance + "}}}",
        R"({"type": "directional", "intensity": 2, "extras": {"prism": {"emission": )" + c.light_spectrum + "}}}");
    const Scene scene = load_gltf(path);
    const double y_s = integrate_xyz([&](double l) { return evaluate(c.s, float(l)); })[1];
    std::array<double, 3> expected = integrate_xyz([&](double l) { return rho(float(l)) * evaluate(c.s, float(l)); });
    for (double& e : expected) e *= 2 / kPi / y_s;
    check_xyz(render_xyz(scene), expected, 0.005);
  }
}

TEST_CASE("an emitter of spectrum S shows S's colour at the luminance of its glTF factors") {
  const auto dir = test::temp_dir("spectral_emitter");
  for (const char* name : {"LED-B3", "A", "F2"}) {
    INFO(name);
    const auto path = test::write_quad_scene(dir, "emitter",
                                             fmt::format(R"({{"emissiveFactor": [1, 0.5, 0.25],
            "extensions": {{"KHR_materials_emissive_strength": {{"emissiveStrength": 3}}}},
            "pbrMetallicRoughness": {{"baseColorFactor": [0, 0, 0, 1]}},
            "extras": {{"prism": {{"emission": "{}"}}}}}})",
                                                         name));
    const Spectrum s = *named_illuminant(name);
    std::array<double, 3> expected = integrate_xyz([&](double l) { return evaluate(s, float(l)); });
    const double y = 3 * luminance(Rgb{1, 0.5f, 0.25f});  // the factors' luminance: the spectrum keeps it
    const double scale = y / expected[1];
    for (double& e : expected) e *= scale;
    check_xyz(render_xyz(load_gltf(path)), expected, 0.005);
  }
}

TEST_CASE("D65 and E round trip: a D65 emitter or light renders as white RGB does, E at x = y = 1/3") {
  const auto dir = test::temp_dir("spectral_round_trip");
  const std::string emissive =
      R"("emissiveFactor": [1, 1, 1], "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]})";
  const MeanXyz rgb = render_xyz(load_gltf(test::write_quad_scene(dir, "rgb", "{" + emissive + "}")));
  const MeanXyz d65 = render_xyz(
      load_gltf(test::write_quad_scene(dir, "d65", "{" + emissive + R"(, "extras": {"prism": {"emission": "D65"}}})")));
  const MeanXyz e = render_xyz(
      load_gltf(test::write_quad_scene(dir, "e", "{" + emissive + R"(, "extras": {"prism": {"emission": "E"}}})")));
  for (int c = 0; c < 3; ++c) CHECK(d65.value[c] == Approx(rgb.value[c]).epsilon(0.002));
  const double sum = e.value[0] + e.value[1] + e.value[2];
  CHECK(e.value[0] / sum == Approx(1 / 3.0).margin(0.001));
  CHECK(e.value[1] / sum == Approx(1 / 3.0).margin(0.001));
  CHECK(e.value[1] == Approx(1).epsilon(0.002));  // the factors' luminance, 1
  // A light: a white patch lit by a D65 light and by a white one.
  const std::string patch =
      R"({"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0},
          "extensions": {"KHR_materials_specular": {"specularFactor": 0}}})";
  const MeanXyz white_light = render_xyz(
      load_gltf(test::write_quad_scene(dir, "white_light", patch, R"({"type": "directional", "intensity": 2})")));
  const MeanXyz d65_light = render_xyz(load_gltf(
      test::write_quad_scene(dir, "d65_light", patch,
                             R"({"type": "directional", "intensity": 2, "extras": {"prism": {"emission": "D65"}}})")));
  for (int c = 0; c < 3; ++c) CHECK(d65_light.value[c] == Approx(white_light.value[c]).epsilon(0.002));
}

TEST_CASE("a scene without spectral inputs is read as before: RGB emission, no spectral reflectance") {
  const auto dir = test::temp_dir("spectral_none");
  const Scene scene = load_gltf(test::write_quad_scene(
      dir, "plain",
      R"({"emissiveFactor": [1, 0.5, 0.25], "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.6, 0.9, 1]}})",
      R"({"type": "point", "intensity": 5, "color": [1, 0.9, 0.8]})"));
  const Material& m = scene.materials.at(0);
  CHECK_FALSE(m.spectral_emission);
  CHECK(std::holds_alternative<RgbIlluminantSpectrum>(*m.emission));
  CHECK_FALSE(std::get<PbrMaterial>(m.kind).base_reflectance);
  CHECK(std::holds_alternative<RgbIlluminantSpectrum>(scene.point_lights.at(0).intensity));
}
