// The Khronos sample assets of the layered material extensions (clearcoat, sheen, thin film,
// specular colour) load without an "ignoring" warning and render with no invalid sample.
// Skipped without the shared assets (PRISM_SHARED_DIR).

#include <catch2/catch.hpp>

#include "core/base/log.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/test_scenes.h"

using namespace prism;

TEST_CASE("the layered-material sample assets load without warnings and render cleanly", "[shared]") {
  const auto assets = test::shared_dir() / "assets/gltf";
  if (!test::shared_assets_present("assets/gltf")) return;
  const auto dir = test::temp_dir("layered_assets");
  for (const char* name :
       {"ClearcoatWicker", "ClearCoatCarPaint", "SheenCloth", "IridescenceSuzanne", "SpecularTest"}) {
    const auto file = assets / name / "glTF" / (std::string(name) + ".gltf");
    INFO(file.string());
    REQUIRE(std::filesystem::exists(file));
    std::string err;
    const int code = test::run_prism(
        "render \"" + file.string() + "\" -o \"" + (dir / "out.exr").string() + "\" --spp 1 --width 16", &err);
    INFO(err);
    CHECK(code == 0);
    CHECK(err.find("ignoring") == std::string::npos);
    CHECK(err.find("not supported") == std::string::npos);

    log::set_level(log::Level::quiet);
    Scene scene = load_gltf(file);
    log::set_level(log::Level::info);
    scene.environment = RgbIlluminantSpectrum(Rgb{1, 1, 1});
    const CameraDesc camera = scene.cameras.empty() ? framing_camera(scene.world_bounds(), 1.f) : scene.cameras[0];
    const auto img = test::render_rgb(scene, camera, 32, 32, 4, 8);
    CHECK(img.stats.invalid_samples == 0);
    for (float v : img.rgb) REQUIRE(std::isfinite(v));
    CHECK(img.mean(1) > 0);
  }
}
