// Reading spectra and optical constants: the SPECTRUM syntax's tables and files, refractiveindex.info's
// CSV and YAML downloads (equal to the catalogue's tables of the same data), and the glTF extras
// that use them, with one clear error for each kind of bad input.

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "core/base/data_path.h"
#include "core/base/error.h"
#include "core/base/table_file.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/refractive_index_file.h"
#include "core/scene/spectrum_input.h"
#include "materials/catalogue.h"
#include "materials/fresnel.h"
#include "spectral/cie.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

void write(const std::filesystem::path& file, const std::string& text) { std::ofstream(file) << text; }

// R(θ, λ) of two conductors agree to 1e-6 at every nm of the visible and four angles.
void check_same_reflectance(const Spectrum& n1, const Spectrum& k1, const Spectrum& n2, const Spectrum& k2) {
  double worst = 0;
  for (int l = int(kLambdaMin); l <= int(kLambdaMax); ++l)
    for (const float cos_theta : {1.f, 0.866f, 0.5f, 0.087f})
      worst = std::max(worst,
                       double(std::abs(fresnel_conductor(cos_theta, evaluate(n1, float(l)), evaluate(k1, float(l))) -
                                       fresnel_conductor(cos_theta, evaluate(n2, float(l)), evaluate(k2, float(l))))));
  CHECK(worst <= 1e-6);
}

}  // namespace

TEST_CASE("a spectrum file: two columns, a header line and comments allowed, 0 outside its points") {
  const TabulatedSpectrum s = parse_spectrum_csv("# measured\nwavelength_nm,value\r\n400, 0.5\n500;0.25\n600\t1\n",
                                                 SpectrumUse::reflectance, "test");
  CHECK(s(400) == 0.5f);
  CHECK(s(450) == Approx(0.375f));
  CHECK(s(600) == 1.f);
  CHECK(s(399) == 0.f);
  CHECK(s(601) == 0.f);
  // An index holds its end values instead.
  CHECK(parse_spectrum_csv("400,1.5\n700,1.4\n", SpectrumUse::index, "n")(800) == 1.4f);
}

TEST_CASE("bad spectra are refused with one message naming what and why") {
  const auto csv = [](const std::string& text, SpectrumUse use = SpectrumUse::reflectance) {
    return test::error_of([&] { parse_spectrum_csv(text, use, "paint.csv"); });
  };
  CHECK(csv("").find("paint.csv: the table is empty") != std::string::npos);
  CHECK(csv("wavelength,value\n").find("empty") != std::string::npos);
  CHECK(csv("500,0.5\n400,0.5\n").find("wavelengths must increase") != std::string::npos);
  CHECK(csv("400,0.5\n400,0.6\n").find("wavelengths must increase") != std::string::npos);
  CHECK(csv("400,0.5\n500,1.5\n").find("must be in [0, 1]") != std::string::npos);
  CHECK(csv("400,-0.5\n500,1\n", SpectrumUse::emission).find("non-negative") != std::string::npos);
  CHECK(csv("400,0.5\n500,x\n").find("line 2") != std::string::npos);
  CHECK(csv("400,0.5,7\n").find("not two numbers") != std::string::npos);
  CHECK(csv("40000000,0.5\n").find("100-100000 nm") != std::string::npos);
  const auto arg = [](const std::string& text, SpectrumUse use = SpectrumUse::emission) {
    return test::error_of([&] { parse_spectrum_argument(text, use, "--env-spectrum"); });
  };
  CHECK(arg("D66").find("neither a named spectrum") != std::string::npos);
  CHECK(arg("blackbody:hot").find("blackbody:KELVIN") != std::string::npos);
  CHECK(arg("blackbody:10").find("[100, 1e6] K") != std::string::npos);
  CHECK(arg("D65", SpectrumUse::reflectance).find("names an illuminant") != std::string::npos);
  CHECK(test::error_of([] {
          checked_spectrum(TabulatedSpectrum({900, 950}, {1, 1}, TabulatedSpectrum::Outside::zero),
                           SpectrumUse::emission, "ir lamp");
        }).find("no luminance") != std::string::npos);
}

TEST_CASE("refractiveindex.info's CSV and YAML give the catalogue's conductor to 1e-6 in R(theta, lambda)") {
  // The catalogue's copper (Johnson & Christy's table, nm), written back in the database's two
  // formats (µm), is read as the same metal.
  const MeasuredMetal copper = MaterialCatalogue::standard().metal("Cu");
  const NumericTable table = read_numeric_table(data_file("materials/metals/Cu.csv"));
  const auto& l = table.column("wavelength_nm");
  std::ostringstream csv, yaml;
  csv << "wl,n\n";
  for (size_t i = 0; i < l.size(); ++i) csv << l[i] / 1000 << "," << table.column("n")[i] << "\n";
  csv << "wl,k\n";
  for (size_t i = 0; i < l.size(); ++i) csv << l[i] / 1000 << "," << table.column("k")[i] << "\n";
  yaml << "REFERENCES: |\n    a test\nDATA:\n  - type: tabulated nk\n    data: |\n";
  for (size_t i = 0; i < l.size(); ++i)
    yaml << "        " << l[i] / 1000 << " " << table.column("n")[i] << " " << table.column("k")[i] << "\n";
  for (const std::string& text : {csv.str(), yaml.str()}) {
    const OpticalConstants c = read_refractive_index(text, "Cu");
    REQUIRE(c.k);
    check_same_reflectance(index_spectrum(c.n), *c.k, copper.n, copper.k);
  }
  // The database's own page, where the shared assets are present.
  const auto page = test::shared_dir() / "data/optical-constants/metals/Cu_Johnson.yml";
  if (test::shared_assets_present("data/optical-constants/metals/Cu_Johnson.yml")) {
    std::ifstream in(page);
    std::stringstream text;
    text << in.rdbuf();
    const OpticalConstants c = read_refractive_index(text.str(), page.string());
    REQUIRE(c.k);
    check_same_reflectance(index_spectrum(c.n), *c.k, copper.n, copper.k);
  }
}

TEST_CASE("refractiveindex.info's dispersion formulas give the catalogue's glass") {
  // N-BK7 by its Sellmeier formula (formula 2), and the same coefficients as formula 1 (squared poles).
  const std::string f2 =
      "DATA:\n  - type: formula 2\n    wavelength_range: 0.3 2.5\n"
      "    coefficients: 0 1.03961212 0.00600069867 0.231792344 0.0200179144 1.01046945 103.560653\n";
  const std::string f1 =
      "DATA:\n  - type: formula 1\n    wavelength_range: 0.3 2.5\n"
      "    coefficients: 0 1.03961212 0.0774616484 0.231792344 0.141484744 1.01046945 10.1765722\n";
  const IorModel bk7 = MaterialCatalogue::standard().dielectric("N-BK7");
  for (const std::string& text : {f2, f1}) {
    const OpticalConstants c = read_refractive_index(text, "N-BK7");
    CHECK_FALSE(c.k);
    for (float l : {400.f, 486.1f, 587.6f, 656.3f, 800.f}) CHECK(ior(c.n, l) == Approx(ior(bk7, l)).epsilon(2e-6));
  }
  // A Cauchy formula (5) is tabulated at every nm: n = 1.5 + 0.004 / λ².
  const OpticalConstants cauchy = read_refractive_index(
      "DATA:\n  - type: formula 5\n    wavelength_range: 0.2 1.0\n    coefficients: 1.5 0.004 -2\n", "cauchy");
  CHECK(ior(cauchy.n, 500) == Approx(1.5 + 0.004 / 0.25).epsilon(1e-6));
  CHECK(test::error_of([] {
          read_refractive_index("DATA:\n  - type: formula 12\n    wavelength_range: 0.3 1\n    coefficients: 1\n", "x");
        }).find("formula 12") != std::string::npos);
  CHECK(test::error_of([] { read_refractive_index("wl,n\n0.5,1.5\n0.4,1.6\n", "y"); }).find("must increase") !=
        std::string::npos);
  CHECK(test::error_of([] { read_refractive_index("0.5,1.5\n", "z"); }).find("wl,n") != std::string::npos);
}

TEST_CASE("a glTF material's extras take spectra, metals and glasses from tables and files in its folder") {
  const auto dir = test::temp_dir("spectral_extras");
  write(dir / "paint.csv", "400,0.2\n700,0.8\n");
  write(dir / "gold.csv", "wl,n\n0.4,1.5\n0.7,0.15\nwl,k\n0.4,1.9\n0.7,4.0\n");
  const auto load = [&](const std::string& extras, const std::string& extensions = "") {
    return load_gltf(test::write_quad_scene(dir, "m",
                                            R"({"emissiveFactor": [1, 1, 1], "pbrMetallicRoughness":
        {"baseColorFactor": [0.5, 0.5, 0.5, 1]})" +
                                                extensions + R"(, "extras": {"prism": )" + extras + "}}"));
  };
  {
    const Scene s = load(R"({"reflectance": {"file": "paint.csv"}, "emission": {"blackbody": 3000}})");
    const Material& m = s.materials.at(0);
    const PbrMaterial& p = std::get<PbrMaterial>(m.kind);
    REQUIRE(p.base_reflectance);
    CHECK(evaluate(*p.base_reflectance, 550) == Approx(0.5));
    CHECK(p.base_color == Rgb{1, 1, 1});  // the factor gives way to the spectrum
    CHECK(m.spectral_emission);
    CHECK(spectrum_to_xyz(*m.emission).y == Approx(1).epsilon(1e-3));  // the factors' luminance
  }
  {
    const PbrMaterial p = std::get<PbrMaterial>(load(R"({"metal": {"nk": "gold.csv"}})").materials.at(0).kind);
    REQUIRE(p.metal);
    CHECK(p.metallic == 1);
    CHECK(evaluate(p.metal->k, 550) == Approx(2.95));
  }
  {
    const PbrMaterial p = std::get<PbrMaterial>(
        load(
            R"({"glass": {"sellmeier": [1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653]}})")
            .materials.at(0)
            .kind);
    CHECK(p.transmission == 1);
    CHECK(p.dielectric.dispersive);
    CHECK(ior(p.dielectric.ior, 587.56f) == Approx(1.5168).epsilon(1e-4));
  }
  {
    const PbrMaterial p =
        std::get<PbrMaterial>(load(R"({"attenuation": {"wavelengths": [400, 700], "values": [0.5, 0.5]}})",
                                   R"(, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                 "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2}})")
                                  .materials.at(0)
                                  .kind);
    REQUIRE(p.dielectric.interior.sigma_a);
    CHECK(evaluate(*p.dielectric.interior.sigma_a, 550) == Approx(std::log(2.0) / 2).epsilon(1e-5));
  }
  // Bad input: one error naming the file, the material and the problem.
  const auto error = [&](const std::string& extras, const std::string& extensions = "") {
    return test::error_of([&] { load(extras, extensions); });
  };
  const std::string outside = (dir.parent_path() / "elsewhere.csv").string();
  write(outside, "400,0.5\n700,0.5\n");
  CHECK(error(R"({"reflectance": "Unobtanium"})").find("names an illuminant") != std::string::npos);
  CHECK(error(R"({"emission": "Unobtanium"})").find("no spectrum is named 'Unobtanium'") != std::string::npos);
  CHECK(error(R"({"reflectance": {"wavelengths": [], "values": []}})").find("empty") != std::string::npos);
  CHECK(error(R"({"reflectance": {"wavelengths": [500, 400], "values": [0.1, 0.2]}})").find("must increase") !=
        std::string::npos);
  CHECK(error(R"({"reflectance": {"wavelengths": [400, 500], "values": [0.1, -0.2]}})").find("in [0, 1]") !=
        std::string::npos);
  CHECK(error(R"({"reflectance": {"file": "../elsewhere.csv"}})").find("outside the scene's folder") !=
        std::string::npos);
  CHECK(error(R"({"reflectance": {"file": "missing.csv"}})").find("no such file") != std::string::npos);
  CHECK(error(R"({"metal": {"nk": "paint.csv"}})").find("wl,n") != std::string::npos);
  CHECK(error(R"({"attenuation": {"wavelengths": [400, 700], "values": [0.5, 0.5]}})")
            .find("needs KHR_materials_volume") != std::string::npos);
  for (const std::string& e : {error(R"({"reflectance": "Unobtanium"})"), error(R"({"metal": {"nk": "paint.csv"}})")}) {
    CHECK(e.find("m.gltf") != std::string::npos);
    CHECK(e.find("material 0") != std::string::npos);
  }
}

TEST_CASE("a light's extras give its emission spectrum, at the luminance of its glTF intensity") {
  const auto dir = test::temp_dir("spectral_light");
  const Scene s = load_gltf(test::write_quad_scene(
      dir, "l", R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}})",
      R"({"type": "point", "intensity": 5, "color": [1, 0.5, 0.5], "extras": {"prism": {"emission": "LED-B1"}}})"));
  const Spectrum& intensity = s.point_lights.at(0).intensity;
  CHECK_FALSE(std::holds_alternative<RgbIlluminantSpectrum>(intensity));  // the file's shape, not the RGB's
  CHECK(luminance(intensity) == Approx(5 * luminance(Rgb{1, 0.5f, 0.5f})).epsilon(1e-5));
}
