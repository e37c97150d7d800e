// The default scene through the real CLI: an EXR with the right metadata, a preview, no invalid
// samples.

#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStandardAttributes.h>
#include <ImfStringAttribute.h>

#include <catch2/catch.hpp>

#include "core/base/log.h"
#include "core/render/image_output.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/test_scenes.h"

using namespace prism;

TEST_CASE("the default scene renders at low spp with zero invalid samples") {
  const auto dir = test::temp_dir("default_scene");
  const auto exr = dir / "default.exr", png = dir / "default.png";
  std::string err;
  const int code = test::run_prism("render \"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\" -o \"" + exr.string() +
                                       "\" --preview \"" + png.string() + "\" --spp 4 --width 64 --quiet",
                                   &err);
  INFO(err);
  REQUIRE(code == 0);
  REQUIRE(std::filesystem::exists(exr));
  REQUIRE(std::filesystem::exists(png));

  Imf::InputFile in(exr.c_str());
  const auto* invalid = in.header().findTypedAttribute<Imf::StringAttribute>("prism.invalidSamples");
  REQUIRE(invalid);
  CHECK(invalid->value() == "0");
  REQUIRE(Imf::hasChromaticities(in.header()));
  CHECK(Imf::chromaticities(in.header()).red.x == Approx(0.64f).margin(1e-4));
  const auto* features = in.header().findTypedAttribute<Imf::StringAttribute>("prism.sceneFeatures");
  REQUIRE(features);
  CHECK(features->value().find("emissive_triangles") != std::string::npos);

  const RgbImage img = read_exr(exr);
  CHECK(img.width == 64);
  CHECK(img.height == 64);
  double sum = 0;
  for (float v : img.rgb) {
    REQUIRE(std::isfinite(v));
    sum += v;
  }
  CHECK(sum > 0);
}

TEST_CASE("the output colour space sets the pixel values and the chromaticities attribute") {
  const auto dir = test::temp_dir("colorspace");
  const auto exr = dir / "aces.exr";
  REQUIRE(test::run_prism("render \"" PRISM_SOURCE_DIR "/data/scenes/cornell.gltf\" -o \"" + exr.string() +
                          "\" --spp 1 --width 16 --colorspace ACEScg --half --quiet") == 0);
  Imf::InputFile in(exr.c_str());
  CHECK(Imf::chromaticities(in.header()).red.x == Approx(0.713f).margin(1e-4));
  CHECK(Imf::chromaticities(in.header()).white.x == Approx(0.32168f).margin(1e-4));
}

TEST_CASE("every shared glTF asset renders at low spp with zero invalid samples", "[shared]") {
  log::set_level(log::Level::quiet);
  for (const auto& file : test::shared_gltf_assets()) {
    INFO(file.string());
    Scene scene = load_gltf(file);
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});  // light every surface, even in unlit assets
    const CameraDesc camera = scene.cameras.empty() ? framing_camera(scene.world_bounds(), 1.f) : scene.cameras[0];
    const auto img = test::render_rgb(scene, camera, 24, 24, 2, 8);
    CHECK(img.stats.invalid_samples == 0);
    for (float v : img.rgb) REQUIRE(std::isfinite(v));
    CHECK(img.mean(1) > 0);
  }
  log::set_level(log::Level::info);
}
