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
#include "materials/ior.h"
#include "tests/support/gltf_builder.h"
#include "tests/support/test_scenes.h"

using namespace prism;

namespace {

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
    // A coefficient of 0 is none: a medium whose sigma_s is 0 does not scatter.
    const Scene clear = load_gltf(write_scene(dir, kVolume, R"({"medium": {"sigma_s": 0, "sigma_a": 2}})"));
    CHECK_FALSE(clear.materials.at(0).dielectric()->interior.scatters());
    CHECK_FALSE(analyze_features(clear).scattering);
    const SceneFeatures f = analyze_features(s);
    CHECK(f.scene_medium);
    CHECK(f.scattering);
  }
}

TEST_CASE("KHR_materials_volume_scatter and extras subsurface: a colour and a distance become a scattering medium") {
  const auto dir = test::temp_dir("gltf_scatter");
  {  // the draft: attenuation is the extinction, multiscatterColor the albedo after many bounces
    const Scene s = load_gltf(write_scene(dir, R"("pbrMetallicRoughness": {"metallicFactor": 0},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
          "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 0.5,
                                   "attenuationColor": [0.2, 0.2, 0.2]},
          "KHR_materials_volume_scatter": {"multiscatterColor": [0.8, 0.8, 0.8], "scatterAnisotropy": 0.4}})",
                                          ""));
    const Dielectric* d = s.materials.at(0).dielectric();
    REQUIRE(d);
    REQUIRE(d->interior.scatters());
    const float sigma_t = -std::log(0.2f) / 0.5f;
    const float s550 = evaluate(*d->interior.sigma_s, 550), a550 = evaluate(*d->interior.sigma_a, 550);
    CHECK(s550 + a550 == Approx(sigma_t).epsilon(0.02));  // the grey upsampled to within 2% at 550 nm
    CHECK(s550 / (s550 + a550) == Approx(single_scattering_albedo(0.8f)).epsilon(0.01));
    CHECK(d->interior.phase.g == Approx(0.4f));
  }
  {  // extras subsurface: the base colour is the medium's, the surface a clear interface of its index
    const Scene s = load_gltf(write_scene(dir, R"("pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.5, 1],
        "metallicFactor": 0, "roughnessFactor": 0.4}, "extensions": {"KHR_materials_ior": {"ior": 1.4}})",
                                          R"({"subsurface": {"mean_free_path": 0.002, "g": 0.2}})"));
    const Material& m = s.materials.at(0);
    const PbrMaterial& p = std::get<PbrMaterial>(m.kind);
    const Dielectric* d = m.dielectric();
    REQUIRE(d);
    CHECK_FALSE(d->thin_walled);
    CHECK(p.transmission == 1);
    CHECK(p.roughness == Approx(0.4f));
    CHECK(p.base_color == Rgb{1, 1, 1});
    CHECK(ior(d->ior, 550) == Approx(1.4f));
    const float red = evaluate(*d->interior.sigma_s, 650), blue = evaluate(*d->interior.sigma_s, 450);
    CHECK(red + evaluate(*d->interior.sigma_a, 650) == Approx(500));  // 1 / mean free path
    CHECK(red > blue);  // a reddish colour scatters red light more and absorbs it less
    CHECK(d->interior.phase.g == Approx(0.2f));
  }
  const auto error = [&](const std::string& prism) {
    return test::error_of([&] { load_gltf(write_scene(dir, "", prism)); });
  };
  CHECK(error(R"({"subsurface": {"mean_free_path": 0}})").find("positive number of metres") != std::string::npos);
  CHECK(error(R"({"subsurface": {"g": 0.5}})").find("mean_free_path") != std::string::npos);
  CHECK(error(R"({"subsurface": {"mean_free_path": 1, "radius": 2}})").find("unknown key") != std::string::npos);
}

TEST_CASE("a bad medium gives one error naming the file, the material and the problem") {
  const auto dir = test::temp_dir("gltf_media_errors");
  const auto error = [&](const std::string& extensions, const std::string& prism, const std::string& scene = "") {
    return test::error_of([&] { load_gltf(write_scene(dir, extensions, prism, scene)); });
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
  has(error(kVolume, R"({"medium": {"sigma_s": 1}, "metal": "Au"})"), "a metal has no medium");
  CHECK(error(kVolume, R"({"medium": {"sigma_s": -1}})").find("material 0") != std::string::npos);
}
