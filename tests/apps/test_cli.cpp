// The prism command line: subcommands' output formats and errors.

#include <catch2/catch.hpp>

#include "support/test_scenes.h"

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
