// Media in a glTF file's extras (README, "Media"): a material's {"medium": …} fills its closed
// volume, the scene's fills the space around everything (fog); coefficients are numbers or
// SPECTRUM values per metre; bad ones give one error naming the file, the place and the problem.

#include <catch2/catch.hpp>
#include <fstream>
#include <functional>
#include <sstream>

#include "core/base/error.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene_features.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

const char* kVolume = R"("pbrMetallicRoughness": {"metallicFactor": 0},
                          "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                          "KHR_materials_volume": {"thicknessFactor": 1}})";

// The quad scene with a material of `extensions` (JSON members) and extras.prism `prism`, and the
// scene's own extras.prism `scene_prism` (none when empty).
std::filesystem::path write_scene(const std::filesystem::path& dir, const std::string& extensions,
                                  const std::string& prism, const std::string& scene_prism = "") {
  std::string material = "{" + extensions;
  if (!prism.empty()) material += std::string(extensions.empty() ? "" : ", ") + R"("extras": {"prism": )" + prism + "}";
  material += "}";
  const auto file = test::write_quad_scene(dir, "media", material);
  if (scene_prism.empty()) return file;
  std::stringstream text;
  text << std::ifstream(file).rdbuf();
  std::string json = text.str();
  const std::string scenes = R"("scenes": [{)";
  const size_t at = json.find(scenes);
  REQUIRE(at != std::string::npos);
  json.insert(at + scenes.size(), R"("extras": {"prism": )" + scene_prism + "}, ");
  std::ofstream(file) << json;
  return file;
}

}  // namespace

TEST_CASE("a material's medium fills its closed volume; the scene's fills the space around") {
  const auto dir = test::temp_dir("gltf_media");
  std::ofstream(dir / "milk.csv") << "400,900\n700,1100\n";
  {
    const Scene s = load_gltf(
        write_scene(dir, kVolume, R"({"medium": {"sigma_s": {"file": "milk.csv"}, "sigma_a": 0.5, "g": 0.8}})"));
    const Dielectric* d = s.materials.at(0).dielectric();
    REQUIRE(d);
    CHECK(d->interior.scatters());
    CHECK(evaluate(*d->interior.sigma_s, 550) == Approx(1000));
    CHECK(evaluate(*d->interior.sigma_s, 800) == Approx(1100));  // a coefficient holds its end values
    CHECK(evaluate(*d->interior.sigma_a, 550) == Approx(0.5));
    CHECK(d->interior.phase.g == Approx(0.8f));
    const SceneFeatures f = analyze_features(s);
    CHECK(f.scattering);
    CHECK(f.absorption);
    CHECK_FALSE(f.scene_medium);
  }
  {  // the volume extension's attenuation stays the absorption when the medium gives none
    const Scene s = load_gltf(write_scene(dir, R"("pbrMetallicRoughness": {"metallicFactor": 0},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
        "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2, "attenuationColor": [0.5, 0.5, 0.5]}})",
                                          R"({"medium": {"sigma_s": 3}})"));
    const Dielectric* d = s.materials.at(0).dielectric();
    REQUIRE(d);
    REQUIRE(d->interior.sigma_a);
    CHECK(evaluate(*d->interior.sigma_a, 550) == Approx(std::log(2.0) / 2).epsilon(1e-2));
    CHECK(evaluate(*d->interior.sigma_s, 550) == Approx(3));
  }
  {
    const Scene s = load_gltf(write_scene(dir, "", "", R"({"medium": {"sigma_s": 0.02, "sigma_a": 0.001}})"));
    REQUIRE(s.medium);
    CHECK(evaluate(*s.medium->sigma_s, 500) == Approx(0.02));
    CHECK(s.medium->phase.g == 0);
    const SceneFeatures f = analyze_features(s);
    CHECK(f.scene_medium);
    CHECK(f.scattering);
  }
}

TEST_CASE("a bad medium gives one error naming the file, the material and the problem") {
  const auto dir = test::temp_dir("gltf_media_errors");
  const auto error = [&](const std::string& extensions, const std::string& prism, const std::string& scene = "") {
    return error_of([&] { load_gltf(write_scene(dir, extensions, prism, scene)); });
  };
  const auto has = [](const std::string& e, const std::string& part) {
    INFO(e);
    CHECK(e.find("media.gltf") != std::string::npos);
    CHECK(e.find(part) != std::string::npos);
  };
  has(error(kVolume, R"({"medium": {"sigma_s": -1}})"), "non-negative");
  has(error(kVolume, R"({"medium": {"sigma_s": {"wavelengths": [400, 700], "values": [1, -2]}}})"), "non-negative");
  has(error(kVolume, R"({"medium": {"sigma_s": 1, "g": 1}})"), "(-1, 1)");
  has(error(kVolume, R"({"medium": {"sigma_t": 1}})"), "unknown key \"sigma_t\"");
  has(error(kVolume, R"({"medium": 3})"), "a medium is");
  has(error(kVolume, R"({"medium": {"sigma_s": {"file": "missing.csv"}}})"), "no such file");
  has(error("", R"({"medium": {"sigma_s": 1}})"), "needs a closed transmissive volume");
  has(error(
          R"("pbrMetallicRoughness": {"metallicFactor": 0}, "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
      "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2}})",
          R"({"medium": {"sigma_a": 1}})"),
      "give one");
  has(error(kVolume, "{}", R"({"medium": {"g": 2}})"), "scene 0: extras.prism.medium.g");
  CHECK(error(kVolume, R"({"medium": {"sigma_s": -1}})").find("material 0") != std::string::npos);
}
