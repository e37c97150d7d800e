// The prism command line: subcommands' output formats and errors.

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>
#include <fmt/format.h>

#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/render/image_output.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

TEST_CASE("prism fresnel prints reflectance as CSV") {
  std::string csv;
  REQUIRE(test::run_prism("fresnel --material Cu --wavelengths 450,550,650 --angles 0,45,60,80,89 --format csv",
                          nullptr, &csv) == 0);
  CHECK(csv.rfind("material,wavelength_nm,angle_deg,R,Rs,Rp\n", 0) == 0);
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 3 * 5);
  CHECK(csv.find("Cu,550,0,0.6235") != std::string::npos);
  CHECK(csv.find("Cu,550,89,0.960") != std::string::npos);
}

TEST_CASE("prism fresnel prints metal colours, takes n,k pairs and plots R(lambda)") {
  const auto dir = test::temp_dir("fresnel_plot");
  const auto png = dir / "r.png";
  std::string text;
  REQUIRE(test::run_prism("fresnel -m Au,Ag --nk 1.5,0 --angles 0 --colorspace ACEScg --plot \"" + png.string() + "\"",
                          nullptr, &text) == 0);
  CHECK(text.find("colour of the reflectance under D65, ACEScg") != std::string::npos);
  CHECK(text.find("n=1.5 k=0") != std::string::npos);
  CHECK(std::filesystem::file_size(png) > 1000);
  std::string err;
  CHECK(test::run_prism("fresnel --material Unobtainium", &err) == 1);
  CHECK(err.find("Unobtainium") != std::string::npos);
  CHECK(err.find("Cu") != std::string::npos);  // the message lists what exists
  CHECK(test::run_prism("fresnel -m Cu --angles 95") == 1);
}

TEST_CASE("prism render --env-map: renders with an image, and refuses bad files and option mixes") {
  const auto dir = test::temp_dir("env_cli");
  const std::string scene = "render \"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\" --spp 1 --width 8 --height 8 -o ";
  const auto sky = dir / "sky.exr", out = dir / "out.exr";
  write_exr(sky,
            {4,
             2,
             std::vector<float>(4 * 2 * 3, 0.5f),
             ColorPipeline::standard().chromaticities(ColorPipeline::kDefaultOutput),
             {}},
            false);
  std::string err;
  const int code = test::run_prism(
      scene + "\"" + out.string() + "\" --env-map \"" + sky.string() + "\" --env-rotate 90 --env-scale 2 --quiet",
      &err);
  INFO(err);
  CHECK(code == 0);
  CHECK(std::filesystem::exists(out));
  std::filesystem::remove(out);

  // A missing or unreadable map stops before rendering, naming the file.
  CHECK(test::run_prism(scene + "\"" + out.string() + "\" --env-map \"" + (dir / "absent.hdr").string() + "\"", &err) ==
        1);
  CHECK(err.find("absent.hdr") != std::string::npos);
  std::ofstream(dir / "junk.hdr") << "not an image";
  CHECK(test::run_prism(scene + "\"" + out.string() + "\" --env-map \"" + (dir / "junk.hdr").string() + "\"", &err) ==
        1);
  CHECK(err.find("junk.hdr") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));

  // --env and --env-map exclude each other; rotation and scale need a map (usage errors).
  const auto usage_error = [&](const std::string& options) {
    std::string message;
    const int code = test::run_prism(scene + "\"" + out.string() + "\" " + options, &message);
    INFO(options << ": " << message);
    CHECK(code != 0);
    CHECK(message.find("env") != std::string::npos);
  };
  usage_error("--env 1,1,1 --env-map \"" + sky.string() + "\"");
  usage_error("--env 1,1,1 --env-rotate 2");
  usage_error("--env-map \"" + sky.string() + "\" --env-scale -1");
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("prism converge writes the error table, the plot and the summary") {
  const auto dir = test::temp_dir("converge");
  std::string err;
  const int code = test::run_prism("converge \"" PRISM_SOURCE_DIR
                                   "/data/scenes/cornell.gltf\" --width 16 --height 16 "
                                   "--max-spp 4 --reference-spp 16 --reference \"" +
                                       (dir / "ref.exr").string() + "\" --out \"" + dir.string() + "\"",
                                   &err);
  INFO(err);
  REQUIRE(code == 0);
  CHECK(std::filesystem::exists(dir / "ref.exr"));
  CHECK(std::filesystem::file_size(dir / "convergence.png") > 1000);
  std::ifstream csv(dir / "convergence.csv");
  std::string line;
  std::getline(csv, line);
  CHECK(line == "configuration,spp,seconds,rmse,relative_mse,mean_error");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 8 * 3);  // eight configurations at 1, 2 and 4 spp
  std::ifstream md(dir / "summary.md");
  std::stringstream summary;
  summary << md.rdbuf();
  CHECK(summary.str().find("independent sampler") != std::string::npos);
  // A reference of another size is refused.
  CHECK(test::run_prism("converge \"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\" --width 8 --height 8 --max-spp 1 "
                        "--reference \"" +
                        (dir / "ref.exr").string() + "\" --out \"" + dir.string() + "\"") == 1);
}

TEST_CASE(
    "prism converge --light-samplers compares light samplers by relative error, and the header records the one "
    "rendered with") {
  const auto dir = test::temp_dir("converge_light_samplers");
  const std::string scene = "\"" PRISM_SOURCE_DIR "/data/scenes/lamp_hall.gltf\"";
  std::string err;
  int code = test::run_prism("converge " + scene + " --width 16 --height 9 --max-spp 2 --reference-spp 4 " +
                                 "--light-samplers power,tree --error relative --reference \"" +
                                 (dir / "ref.exr").string() + "\" --out \"" + dir.string() + "\"",
                             &err);
  INFO(err);
  REQUIRE(code == 0);
  std::ifstream md(dir / "summary.md");
  std::stringstream summary;
  summary << md.rdbuf();
  CHECK(summary.str().find("light sampler power") != std::string::npos);
  CHECK(summary.str().find("light sampler tree") != std::string::npos);
  CHECK(summary.str().find("Stated error: relative RMSE") != std::string::npos);
  CHECK(test::run_prism("converge " + scene + " --width 16 --height 9 --light-samplers power,nearest --reference \"" +
                        (dir / "ref.exr").string() + "\" --out \"" + dir.string() + "\"") == 2);
  // A render logs the tree it built and names the sampler in the header.
  const auto out = dir / "hall.exr";
  code = test::run_prism("render " + scene + " --width 16 --height 9 --spp 1 -o \"" + out.string() + "\"", &err);
  REQUIRE(code == 0);
  CHECK(err.find("light tree:") != std::string::npos);
  Imf::InputFile in(out.c_str());
  const auto* sampler = in.header().findTypedAttribute<Imf::StringAttribute>("prism.lightSampler");
  REQUIRE(sampler != nullptr);
  CHECK(sampler->value() == "auto");
}

TEST_CASE("prism converge --seconds compares the chosen integrators at equal time and names the one to use") {
  const auto dir = test::temp_dir("converge_equal_time");
  std::string err;
  const int code =
      test::run_prism("converge \"" PRISM_SOURCE_DIR
                      "/data/scenes/cornell.gltf\" --width 16 --height 16 --reference-spp 16 "
                      "--reference-integrator bdpt --integrators path,bdpt,vcm --seconds 0.2 --reference \"" +
                          (dir / "ref.exr").string() + "\" --out \"" + dir.string() + "\"",
                      &err);
  INFO(err);
  REQUIRE(code == 0);
  std::ifstream csv(dir / "equal_time.csv");
  std::string line;
  std::getline(csv, line);
  CHECK(line == "configuration,seconds,spp,relative_rmse,relative_rmse_at_budget,mean_error");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 3);
  std::ifstream md(dir / "summary.md");
  std::stringstream summary;
  summary << md.rdbuf();
  CHECK(summary.str().find("for this scene") != std::string::npos);
  // An unknown integrator is a usage error.
  CHECK(test::run_prism("converge \"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\" --integrators path,mlt "
                        "--seconds 1 --reference \"" +
                        (dir / "ref.exr").string() + "\" --out \"" + dir.string() + "\"") == 2);
}

TEST_CASE("prism compare: an image's error against a reference, linear and as displayed, and two seeds' error") {
  const auto dir = test::temp_dir("compare");
  const auto constant = [&](const char* name, float value, int width) {
    const std::filesystem::path file = dir / name;
    write_exr(file, {width, 4, std::vector<float>(size_t(width) * 4 * 3, value), {}, {}}, false);
    return fmt::format("\"{}\"", file.string());
  };
  const std::string a = constant("a.exr", 0.5f, 4), b = constant("b.exr", 0.25f, 4);
  // The sRGB encoding of 0.5 and 0.25: 1.055 x^(1/2.4) − 0.055.
  const double ea = 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, eb = 1.055 * std::pow(0.25, 1 / 2.4) - 0.055;
  const auto value = [](const std::string& out, const std::string& key) {
    const size_t at = out.find(key + "=");
    REQUIRE(at != std::string::npos);
    return std::stod(out.substr(at + key.size() + 1));
  };
  std::string out;
  REQUIRE(test::run_prism("compare " + a + " " + b, nullptr, &out) == 0);
  CHECK(value(out, "rmse") == Approx(0.25));
  CHECK(value(out, "relative_rmse") == Approx(1.0));
  CHECK(value(out, "display_relative_rmse") == Approx((ea - eb) / eb).epsilon(1e-5));
  CHECK(value(out, "reference_mean") == Approx(0.25));
  REQUIRE(test::run_prism("compare --independent " + a + " " + b, nullptr, &out) == 0);
  CHECK(value(out, "relative_rmse") == Approx(1 / std::sqrt(2.0)));
  REQUIRE(test::run_prism("compare " + a + " " + a, nullptr, &out) == 0);
  CHECK(value(out, "rmse") == 0);
  std::string err;
  CHECK(test::run_prism("compare " + a + " " + constant("wide.exr", 0.25f, 8), &err) == 1);
  CHECK(err.find("only images of one size compare") != std::string::npos);
}

// The rows of a `prism measure` CSV: x, y, z, nx, ny, nz, illuminance, standard error.
static std::vector<std::array<double, 8>> read_readings(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  CHECK(line == "x,y,z,nx,ny,nz,illuminance_lux,std_error_lux");
  std::vector<std::array<double, 8>> rows;
  while (std::getline(in, line)) {
    std::array<double, 8> row{};
    char comma;
    std::istringstream cells(line);
    cells >> row[0];
    for (int c = 1; c < 8; ++c) cells >> comma >> row[c];
    CHECK(cells);
    rows.push_back(row);
  }
  return rows;
}

TEST_CASE("prism measure: lux at given points and on a named node's grid, with its isolux map") {
  // A 2 m square desk top at y = 0.5 (node "Desk", mesh "desk_top") under a 4 cd point light at
  // y = 2.5: a meter facing up at (x, y, z) reads E = I h / d³, h = 2.5 − y, to within the noise of
  // the sampled wavelengths (the reading's own standard error, which must be small).
  const auto dir = test::temp_dir("measure_cli");
  test::GltfBuilder b;
  const int pos = b.floats({-1, 0, -1, -1, 0, 1, 1, 0, 1, 1, 0, -1}, "VEC3");
  const int idx = b.u16({0, 1, 2, 0, 2, 3});
  std::ofstream(dir / "desk.gltf") << b.json(fmt::format(R"(
  "extensionsUsed": ["KHR_lights_punctual"],
  "extensions": {{"KHR_lights_punctual": {{"lights": [{{"type": "point", "intensity": 4}}]}}}},
  "scenes": [{{"nodes": [0, 1]}}],
  "nodes": [{{"name": "Desk", "mesh": 0, "translation": [0, 0.5, 0]}},
            {{"name": "Lamp", "translation": [0, 2.5, 0], "extensions": {{"KHR_lights_punctual": {{"light": 0}}}}}}],
  "meshes": [{{"name": "desk_top", "primitives": [{{"attributes": {{"POSITION": {}}}, "indices": {}}}]}}])",
                                                         pos, idx));
  const std::string measure = "measure \"" + (dir / "desk.gltf").string() + "\" --spp 256 --quiet ";
  const auto check_reading = [](const std::array<double, 8>& r) {
    const double h = 2.5 - r[1], d = std::sqrt(r[0] * r[0] + h * h + r[2] * r[2]), expected = 4 * h / (d * d * d);
    INFO("meter at " << r[0] << "," << r[1] << "," << r[2] << ": " << r[6] << " +- " << r[7] << " lux");
    CHECK(r[7] < 0.002 * expected);
    CHECK(std::abs(r[6] - expected) < 4 * r[7]);
  };

  const auto points = dir / "points.csv";
  REQUIRE(test::run_prism(measure + "--point 0,1,0,0,1,0 --point 0.5,0.5,0.5,0,1,0 -o \"" + points.string() + "\"") ==
          0);
  const auto at_points = read_readings(points);
  REQUIRE(at_points.size() == 2);
  CHECK(at_points[0][6] == Approx(4 / 2.25).epsilon(0.005));
  for (const auto& r : at_points) check_reading(r);

  // By the node's name: 4 × 4 meters 0.5 m apart on the desk's top, and a map of them.
  const auto grid = dir / "grid.csv";
  REQUIRE(test::run_prism(measure + "--grid Desk:0.5 -o \"" + grid.string() + "\"") == 0);
  const auto on_desk = read_readings(grid);
  REQUIRE(on_desk.size() == 16);
  for (const auto& r : on_desk) {
    CHECK(r[1] == Approx(0.5).margin(1e-3));
    CHECK(r[4] == 1);
    CHECK(std::abs(std::abs(r[0]) - 0.5) == Approx(0.25));
    check_reading(r);
  }
  std::ifstream png(dir / "grid.png", std::ios::binary);
  char signature[8] = {};
  png.read(signature, 8);
  CHECK(std::string(signature + 1, 3) == "PNG");

  // By the mesh's name, the same meters; the same readings at any thread count.
  const auto by_mesh = dir / "by_mesh.csv";
  REQUIRE(test::run_prism(measure + "--threads 1 --grid desk_top:0.5 -o \"" + by_mesh.string() + "\"") == 0);
  const auto slurp = [](const std::filesystem::path& file) {
    std::ostringstream text;
    text << std::ifstream(file).rdbuf();
    return text.str();
  };
  CHECK(slurp(by_mesh) == slurp(grid));

  // Bad points stop with one message naming what is wrong, and write nothing.
  const auto refused = [&](const std::string& options, const std::string& named) {
    const auto out = dir / "refused.csv";
    std::string err;
    CHECK(test::run_prism(measure + options + " -o \"" + out.string() + "\"", &err) == 1);
    INFO(err);
    CHECK(err.find(named) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
    CHECK_FALSE(std::filesystem::exists(dir / "refused.png"));
  };
  refused("--grid Table:0.5", "Table");
  refused("--grid Desk:0", "Desk:0");
  refused("--grid Desk:1e-30", "4000000");
  refused("--grid 0,0,0,1,0,1,1e30,2", "4000000");
  refused("--point 0,1,0,0,0,0", "0,1,0,0,0,0");
  refused("--point 0,1,0", "0,1,0");
  refused("--point 1e39,1,0,0,1,0", "1e39");
  refused("--point 0,1,0,0,1,0 --grid Desk:0.5", "one way");
}

TEST_CASE("prism fresnel --nk-file reads refractiveindex.info's CSV as the same n, k given by --nk") {
  const auto dir = test::temp_dir("fresnel_nk_file");
  std::ofstream(dir / "flat.csv") << "wl,n\n0.3,0.27\n0.9,0.27\nwl,k\n0.3,3.41\n0.9,3.41\n";
  const std::string query = "fresnel --wavelengths 400,550,700 --angles 0,45,80 --format csv ";
  std::string from_file, from_pair, err;
  REQUIRE(test::run_prism(query + "--nk-file \"" + (dir / "flat.csv").string() + "\"", &err, &from_file) == 0);
  REQUIRE(test::run_prism(query + "--nk 0.27,3.41", &err, &from_pair) == 0);
  // The same rows but for the label in the first column.
  const auto values = [](const std::string& csv) {
    std::vector<std::string> rows;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) rows.push_back(line.substr(line.find(',')));
    return rows;
  };
  CHECK(values(from_file).size() == 1 + 3 * 3);
  CHECK(values(from_file) == values(from_pair));
  std::ofstream(dir / "junk.csv") << "wl,n\n0.5,oops\n";
  CHECK(test::run_prism(query + "--nk-file \"" + (dir / "junk.csv").string() + "\"", &err) == 1);
  CHECK(err.find("junk.csv") != std::string::npos);
}

TEST_CASE(
    "prism render --env-spectrum and --white-balance: a white surface under illuminant A renders orange, "
    "balanced for A neutral") {
  const auto dir = test::temp_dir("white_balance_cli");
  const auto scene = test::write_quad_scene(
      dir, "white", R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0}})");
  const auto render = [&](const std::string& options) {
    const auto out = dir / "out.exr";
    std::string err;
    const int code = test::run_prism("render \"" + scene.string() + "\" --width 8 --height 8 --spp 64 --quiet " +
                                         "--env 1,1,1 --env-spectrum A -o \"" + out.string() + "\" " + options,
                                     &err);
    INFO(options << ": " << err);
    REQUIRE(code == 0);
    const RgbImage image = read_exr(out);
    std::array<double, 3> mean{};
    for (size_t i = 0; i < image.rgb.size(); ++i) mean[i % 3] += image.rgb[i] / double(image.rgb.size() / 3);
    Imf::InputFile in(out.c_str());
    const auto* balance = in.header().findTypedAttribute<Imf::StringAttribute>("prism.whiteBalance");
    return std::pair{mean, balance ? balance->value() : std::string("(none)")};
  };
  // Unbalanced, A's white in linear Rec.709 is about (1.85, 0.83, 0.23) at luminance 1.
  const auto [orange, none] = render("");
  CHECK(orange[0] / orange[2] > 6);
  CHECK(none == "(none)");
  for (const char* white : {"A", "2856"}) {
    const auto [neutral, recorded] = render(std::string("--white-balance ") + white);
    CHECK(neutral[0] / neutral[1] == Approx(1).margin(0.02));
    CHECK(neutral[2] / neutral[1] == Approx(1).margin(0.02));
    CHECK(recorded.find(white) != std::string::npos);
  }
  // Unknown spectra and whites stop before rendering, naming them.
  for (const char* bad : {"--env-spectrum Unobtainium", "--white-balance Unobtainium"}) {
    std::string err;
    CHECK(test::run_prism("render \"" + scene.string() + "\" --width 8 --height 8 --spp 1 --env 1,1,1 -o \"" +
                              (dir / "bad.exr").string() + "\" " + bad,
                          &err) == 1);
    CHECK(err.find("Unobtainium") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "bad.exr"));
  }
}

TEST_CASE("prism render refuses bad output options before it reads the scene") {
  // The scene does not exist: each message must be about the option, found first.
  const std::string render = "render \"" + (test::temp_dir("early_refusals") / "absent.gltf").string() + "\" -o x.exr ";
  for (const auto& [option, named] : std::vector<std::pair<std::string, std::string>>{
           {"--colorspace Bogus", "Bogus"},
           {"--white-balance Bogus", "Bogus"},
           {"--spectral-bins 500,400", "500,400"},
           {"--fog -1", "non-negative"},
           {"--fog 0.1,0,2", "(-1, 1)"},
           {"--fog 1,2,3,4", "SIGMA_S[,SIGMA_A[,G]]"},
       }) {
    std::string err;
    CHECK(test::run_prism(render + option, &err) == 1);
    INFO(option << ": " << err);
    CHECK(err.find(named) != std::string::npos);
    CHECK(err.find("absent.gltf") == std::string::npos);
  }
}
