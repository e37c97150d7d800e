// The prism command line: subcommands' output formats and errors.

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/render/image_output.h"
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
